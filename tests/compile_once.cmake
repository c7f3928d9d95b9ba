# On-demand compilation happens once per machine: two processes that need the same new variant at the same time
# (started together in the background) into a fresh cache; one compiles, the other waits and loads its object.
# Arguments: -DHUBBEAM= -DSCENE= -DCACHE= -DOUT=
file(REMOVE_RECURSE ${CACHE})
set(run "HUBBEAM_CACHE_DIR='${CACHE}' '${HUBBEAM}' run '${SCENE}' --method bsim --ny 7 --nx 0 --t-end 1")
execute_process(
  COMMAND sh -c "${run} -o '${OUT}/compile_once_1.csv' >/dev/null 2>'${OUT}/compile_once_1.err' & a=$!
                 ${run} -o '${OUT}/compile_once_2.csv' >/dev/null 2>'${OUT}/compile_once_2.err' & b=$!
                 wait $a; ea=$?; wait $b; eb=$?; exit $((ea + eb))"
  RESULT_VARIABLE code)
file(READ ${OUT}/compile_once_1.err err1)
file(READ ${OUT}/compile_once_2.err err2)
if(NOT code EQUAL 0)
  message(FATAL_ERROR "exit code ${code}: ${err1}${err2}")
endif()
string(REGEX MATCHALL "compiling variant bsim_nx0_ny7_prescribed_first" compiles "${err1}${err2}")
list(LENGTH compiles n)
if(NOT n EQUAL 1)
  message(FATAL_ERROR "expected one compilation, saw ${n}: ${err1}${err2}")
endif()
