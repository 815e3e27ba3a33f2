# Installs the built needlekit into a scratch prefix, then configures, builds and runs a consumer project that uses
# find_package(needlekit), and (with -DPYTHON=...) imports the installed Python module from the prefix's
# PYTHON_DIR (lib/python3.X/dist-packages: where Debian's python3 looks under /usr/local) and evaluates a design.
# Arguments: -DBUILD_DIR=... -DSOURCE_DIR=... -DWORK_DIR=... [-DPYTHON=/usr/bin/python3 -DPYTHON_DIR=...]
file(REMOVE_RECURSE ${WORK_DIR})
execute_process(COMMAND ${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${WORK_DIR}/prefix
                RESULT_VARIABLE rc OUTPUT_QUIET)
if(rc)
  message(FATAL_ERROR "install failed: ${rc}")
endif()
execute_process(COMMAND ${CMAKE_COMMAND} -S ${SOURCE_DIR}/tests/package/consumer -B ${WORK_DIR}/build
                        -DCMAKE_PREFIX_PATH=${WORK_DIR}/prefix -DCMAKE_BUILD_TYPE=Release
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(rc)
  message(FATAL_ERROR "configuring the consumer failed:\n${out}\n${err}")
endif()
execute_process(COMMAND ${CMAKE_COMMAND} --build ${WORK_DIR}/build RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(rc)
  message(FATAL_ERROR "building the consumer failed:\n${out}\n${err}")
endif()
execute_process(COMMAND ${WORK_DIR}/build/consumer RESULT_VARIABLE rc)
if(rc)
  message(FATAL_ERROR "the consumer computed a wrong performance index (exit ${rc})")
endif()
message(STATUS "find_package(needlekit) consumer: ok")
if(PYTHON)
  set(script "import needlekit, sys\n"
             "assert needlekit.__file__.startswith(sys.argv[1]), needlekit.__file__\n"
             "d = needlekit.ArrayDesign(needle=needlekit.NeedleGeometry(shape='cone', tip_diameter='30 um', "
             "base_diameter='150 um', length='500 um'), material='silicon', width='1 cm')\n"
             "pi = needlekit.performance_index(d).performance_index * 1e-6\n"
             "assert abs(pi / 1.288e-4 - 1) < 5e-4, pi  # dissertation 6.3.1, Table 6.1 solid cone\n")
  execute_process(COMMAND ${CMAKE_COMMAND} -E env PYTHONPATH=${WORK_DIR}/prefix/${PYTHON_DIR}
                          ${PYTHON} -c "${script}" ${WORK_DIR}/prefix
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(rc)
    message(FATAL_ERROR "importing the installed Python module failed:\n${out}\n${err}")
  endif()
  message(STATUS "installed Python module: ok")
endif()
