# On-demand compilation happens once per machine: two processes that need the same new variant at the same time
# (run as a pipeline, so concurrently) into a fresh cache; one compiles, the other waits and loads its object.
# Arguments: -DHUBBEAM= -DSCENE= -DCACHE= -DOUT=
file(REMOVE_RECURSE ${CACHE})
execute_process(
  COMMAND ${CMAKE_COMMAND} -E env HUBBEAM_CACHE_DIR=${CACHE} ${HUBBEAM} run ${SCENE} --method bsim --ny 7 --nx 0
          --t-end 1 -o ${OUT}/compile_once_1.csv
  COMMAND ${CMAKE_COMMAND} -E env HUBBEAM_CACHE_DIR=${CACHE} ${HUBBEAM} run ${SCENE} --method bsim --ny 7 --nx 0
          --t-end 1 -o ${OUT}/compile_once_2.csv
  RESULTS_VARIABLE codes OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT codes STREQUAL "0;0")
  message(FATAL_ERROR "exit codes ${codes}: ${err}")
endif()
string(REGEX MATCHALL "compiling variant bsim_nx0_ny7_prescribed_first" compiles "${err}")
list(LENGTH compiles n)
if(NOT n EQUAL 1)
  message(FATAL_ERROR "expected one compilation, saw ${n}: ${err}")
endif()
