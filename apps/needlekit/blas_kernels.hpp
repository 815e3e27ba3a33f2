// OpenBLAS kernels for the FE commands. Debian bookworm's OpenBLAS 0.3.21 does not recognise some current Xeons (a
// virtual machine's "Intel(R) Xeon(R) Processor" with AVX-512) and falls back to its Prescott (SSE3) kernels: the
// supernodal Cholesky factorizations of the FE, mostly dgemm, ran 1.7x slower (BENCHMARKS.md, "BLAS kernels").
// OpenBLAS reads its kernel choice (OPENBLAS_CORETYPE) once, when it is loaded, before main().
#pragma once

namespace needlekit::cli {

// For a command that runs the FE (indent, insert, reproduce, calibrate): when OpenBLAS chose its Prescott kernels on
// a processor with AVX2 and OPENBLAS_CORETYPE is not set, re-executes the program with OPENBLAS_CORETYPE=Haswell
// (AVX2 kernels). Returns normally otherwise, or when the re-execution fails. The user's OPENBLAS_CORETYPE is kept.
void use_avx2_blas_kernels(int argc, char** argv);

}  // namespace needlekit::cli
