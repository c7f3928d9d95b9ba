# The C++ library as a user gets it: cmake --install into a fresh prefix, then examples/run_scene configured with
# find_package(hubbeam) against that prefix, built, and run on a scene (it checks its own results). Then the
# installed commands with the build and source trees out of reach: each must find its generator and Python package
# relative to itself.
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
# (A program of the user's finds hubbeam-gen through HUBBEAM_GEN when it is not in the configured install folder.)
execute_process(COMMAND ${CMAKE_COMMAND} -E env HUBBEAM_GEN=${WORK}/prefix/bin/hubbeam-gen
                        ${WORK}/build/run_scene ${SOURCE_DIR}/cases/spinup_omega4.toml
                RESULT_VARIABLE code OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT code EQUAL 0 OR NOT out MATCHES "fem_nx4_ny6_prescribed_first: 501 rows")
  message(FATAL_ERROR "the example failed (exit ${code}): ${out}${err}")
endif()
message(STATUS "${out}")

# The installed commands without the build tree. The prefix is copied to a folder of its own outside both trees (so
# that an absolute install path compiled in would be wrong as well), with the scenes beside it; as root, the source
# and build trees are also hidden under empty file systems in a private mount namespace, as if they were removed.
string(RANDOM LENGTH 10 tag)
set(moved /tmp/hubbeam-moved-${tag})
file(COPY ${WORK}/prefix/ DESTINATION ${moved}/prefix)
file(COPY ${SOURCE_DIR}/cases/spinup_omega4.toml ${SOURCE_DIR}/cases/torque_tau10.toml DESTINATION ${moved})
set(hubbeam ${moved}/prefix/bin/hubbeam)
file(WRITE ${moved}/commands.sh "set -e
cd '${moved}'
unset HUBBEAM_GEN PYTHONPATH
export HUBBEAM_CACHE_DIR='${moved}/cache'
echo run; '${hubbeam}' run spinup_omega4.toml --source generated --method amm --nx 1 --ny 3 --t-end 0.5 -o run.csv | grep 'compiled now'
echo modes; '${hubbeam}' modes spinup_omega4.toml --omega 0:4:2 --methods amm -o modes.csv
echo linearize; '${hubbeam}' linearize torque_tau10.toml --omega 2 -o lin
echo sweep; '${hubbeam}' sweep --help
echo plot; '${hubbeam}' plot tip run.csv -o tip
test -s tip.png && test -s run.csv && test -s modes.csv && test -s lin-A.csv
echo all-commands-ran
")
set(hide "")
execute_process(COMMAND id -u OUTPUT_VARIABLE uid OUTPUT_STRIP_TRAILING_WHITESPACE)
execute_process(COMMAND unshare --mount true RESULT_VARIABLE unshare_code OUTPUT_QUIET ERROR_QUIET)
if(uid EQUAL 0 AND unshare_code EQUAL 0)
  # The build tree first: it may lie inside the source tree.
  set(hide "mount -t tmpfs none '${BUILD_DIR}' && mount -t tmpfs none '${SOURCE_DIR}' && ")
  set(command unshare --mount sh -c "${hide}sh '${moved}/commands.sh'")
else()
  message(STATUS "not root or no unshare: the build tree stays visible; only the prefix is moved")
  set(command sh ${moved}/commands.sh)
endif()
execute_process(COMMAND ${command} RESULT_VARIABLE code OUTPUT_VARIABLE out ERROR_VARIABLE err)
file(REMOVE_RECURSE ${moved})
if(NOT code EQUAL 0 OR NOT out MATCHES "all-commands-ran")
  message(FATAL_ERROR "the moved installation without its build tree failed (exit ${code}): ${out}${err}")
endif()
