#include "blas_kernels.hpp"

#include <unistd.h>

#include <cstdlib>
#include <string_view>

extern "C" char* openblas_get_corename();  // OpenBLAS's own API (cblas.h of libopenblas-dev, not installed here)

namespace needlekit::cli {

void use_avx2_blas_kernels(int argc, char** argv) {
  if (argc < 2 || std::getenv("OPENBLAS_CORETYPE") != nullptr) return;
  const std::string_view command = argv[1];
  if (command != "indent" && command != "insert" && command != "reproduce" && command != "calibrate") return;
  const char* core = openblas_get_corename();
  if (core == nullptr || std::string_view(core) != "Prescott" || !__builtin_cpu_supports("avx2")) return;
  if (setenv("OPENBLAS_CORETYPE", "Haswell", 0) != 0) return;
  execv("/proc/self/exe", argv);  // returns only on failure: then run on with the Prescott kernels
}

}  // namespace needlekit::cli
