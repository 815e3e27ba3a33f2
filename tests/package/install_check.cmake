# Installs the built needlekit into a scratch prefix, then configures, builds and runs a consumer project that uses
# find_package(needlekit) (and meshes, through the installed Gmsh module), and runs the installed tool on a command
# that meshes: both must open the module installed in the prefix. With -DPYTHON=..., it also imports the installed
# Python module from the prefix's PYTHON_DIR (lib/python3.X/dist-packages: where Debian's python3 looks under
# /usr/local), evaluates a design and meshes a block through the prefix's Gmsh module.
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
# Each program must open the Gmsh module of the prefix (LD_DEBUG=files: the loader names the module that needs
# libgmsh).
function(expect_module_from_prefix what log)
  string(REGEX MATCH "file=libgmsh[^\n]*needed by ([^\n ]*libneedlekit_gmsh[^\n ]*)" found "${log}")
  if(NOT found OR NOT CMAKE_MATCH_1 MATCHES "^${WORK_DIR}/prefix/")
    message(FATAL_ERROR "${what} did not open the Gmsh module installed in ${WORK_DIR}/prefix (opened: "
                        "'${CMAKE_MATCH_1}')")
  endif()
endfunction()
execute_process(COMMAND ${CMAKE_COMMAND} -E env LD_DEBUG=files ${WORK_DIR}/build/consumer
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE log)
if(rc)
  message(FATAL_ERROR "the consumer computed a wrong performance index or mesh (exit ${rc}):\n${out}")
endif()
expect_module_from_prefix("the consumer" "${log}")
file(WRITE ${WORK_DIR}/block.toml "[tissue]\nwidth = \"1000 um\"\nlength = \"1000 um\"\nheight = \"500 um\"\n"
     "[[tissue.layers]]\nname = \"silicone\"\nthickness = \"rest\"\nyoungs_modulus = \"0.2 MPa\"\n"
     "poisson_ratio = 0.45\n[mesh]\nsize_at_tip = \"100 um\"\nsize_far = \"250 um\"\n")
execute_process(COMMAND ${CMAKE_COMMAND} -E env LD_DEBUG=files ${WORK_DIR}/prefix/bin/needlekit tissue-mesh
                        ${WORK_DIR}/block.toml --threads 1 --out ${WORK_DIR}/tool_out
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE log)
if(rc OR NOT EXISTS ${WORK_DIR}/tool_out/tissue.vtu)
  message(FATAL_ERROR "the installed needlekit tissue-mesh failed (exit ${rc}):\n${out}")
endif()
expect_module_from_prefix("the installed needlekit" "${log}")
message(STATUS "find_package(needlekit) consumer and installed tool (with the Gmsh module): ok")
if(PYTHON)
  string(CONCAT script "import needlekit, sys\n"
                "assert needlekit.__file__.startswith(sys.argv[1]), needlekit.__file__\n"
                "d = needlekit.ArrayDesign(needle=needlekit.NeedleGeometry(shape='cone', tip_diameter='30 um', "
                "base_diameter='150 um', length='500 um'), material='silicon', width='1 cm')\n"
                "pi = needlekit.performance_index(d).performance_index * 1e-6\n"
                "assert abs(pi / 1.288e-4 - 1) < 5e-4, pi  # dissertation 6.3.1, Table 6.1 solid cone\n"
                "block = needlekit.LayeredBlockOptions(width='1 mm', length='1 mm', size_at_site='100 um', "
                "size_far='250 um', threads=1)\n"
                "assert len(needlekit.layered_block_mesh(block).mesh.tets) > 100\n")
  execute_process(COMMAND ${CMAKE_COMMAND} -E env PYTHONPATH=${WORK_DIR}/prefix/${PYTHON_DIR} LD_DEBUG=files
                          ${PYTHON} -c "${script}" ${WORK_DIR}/prefix
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE log)
  if(rc)
    message(FATAL_ERROR "importing the installed Python module failed:\n${out}\n${log}")
  endif()
  expect_module_from_prefix("the installed Python module" "${log}")
  message(STATUS "installed Python module (with the Gmsh module): ok")
endif()
