# Debian's Ceres is a static library whose link interface names ATLAS (libf77blas, libatlas, ATLAS's libblas.so dev
# link). Linked as exported, every BLAS call of the program — Ceres's and CHOLMOD's supernodal dgemm_/dsyrk_, which
# the FE's sparse Cholesky factorizations spend most of their time in — resolves to ATLAS's generic kernels before
# the OpenBLAS that CHOLMOD's libblas.so.3 names: the FE ran 3-8x slower (BENCHMARKS.md). This swaps ATLAS for
# OpenBLAS in Ceres::ceres's link interface. Included after find_package(Ceres) by the build and by needlekitConfig.
find_library(NEEDLEKIT_OPENBLAS_LIBRARY NAMES libopenblas.so.0 openblas REQUIRED)
# Ceres::ceres names the libraries itself; its SuiteSparse targets reach them through FindBLAS's BLAS::BLAS.
foreach(_needlekit_target Ceres::ceres BLAS::BLAS)
  if(TARGET ${_needlekit_target})
    get_target_property(_needlekit_links ${_needlekit_target} INTERFACE_LINK_LIBRARIES)
    list(FILTER _needlekit_links EXCLUDE REGEX "/lib(blas|f77blas|atlas)\\.so$")
    list(APPEND _needlekit_links ${NEEDLEKIT_OPENBLAS_LIBRARY})
    set_target_properties(${_needlekit_target} PROPERTIES INTERFACE_LINK_LIBRARIES "${_needlekit_links}")
  endif()
endforeach()
unset(_needlekit_links)
unset(_needlekit_target)
