# The C++ library as a user gets it: cmake --install into a fresh prefix, then examples/run_scene configured with
# find_package(hubbeam) against that prefix, built, and run on a scene (it checks its own results).
# Arguments: -DBUILD_DIR= -DSOURCE_DIR= -DWORK= -DGENERATOR= -DCXX_FLAGS= (the build's: a sanitizer build's
# libraries need the example instrumented alike)
file(REMOVE_RECURSE ${WORK})
execute_process(COMMAND ${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${WORK}/prefix
                RESULT_VARIABLE code OUTPUT_QUIET ERROR_VARIABLE err)
if(NOT code EQUAL 0)
  message(FATAL_ERROR "cmake --install failed: ${err}")
endif()
execute_process(COMMAND ${CMAKE_COMMAND} -S ${SOURCE_DIR}/examples/run_scene -B ${WORK}/build -G ${GENERATOR}
                        -DCMAKE_PREFIX_PATH=${WORK}/prefix -DCMAKE_BUILD_TYPE=Release "-DCMAKE_CXX_FLAGS=${CXX_FLAGS}"
                RESULT_VARIABLE code OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT code EQUAL 0)
  message(FATAL_ERROR "configuring the example against the installed package failed: ${out}${err}")
endif()
execute_process(COMMAND ${CMAKE_COMMAND} --build ${WORK}/build RESULT_VARIABLE code OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT code EQUAL 0)
  message(FATAL_ERROR "building the example failed: ${out}${err}")
endif()
execute_process(COMMAND ${WORK}/build/run_scene ${SOURCE_DIR}/cases/spinup_omega4.toml
                RESULT_VARIABLE code OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT code EQUAL 0 OR NOT out MATCHES "fem_nx4_ny6_prescribed_first: 501 rows")
  message(FATAL_ERROR "the example failed (exit ${code}): ${out}${err}")
endif()
message(STATUS "${out}")
