# Runs the zero-order model through the 10 rad/s spin-up, above the first bending frequency (2.91 rad/s):
# hubbeam must exit 1 with an "unstable" message and leave the rows computed before the stop in the CSV.
execute_process(COMMAND ${HUBBEAM} run ${SCENE} --order zero --nx 0 -o ${CSV}
                RESULT_VARIABLE code OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT code EQUAL 1)
  message(FATAL_ERROR "expected exit code 1, got ${code}\n${out}\n${err}")
endif()
if(NOT err MATCHES "unstable")
  message(FATAL_ERROR "expected an 'unstable' message on stderr, got: ${err}")
endif()
file(STRINGS ${CSV} rows)
list(LENGTH rows n)
if(n LESS 100)
  message(FATAL_ERROR "expected the rows before the stop to be kept, found ${n} lines")
endif()
message(STATUS "stopped as expected after ${n} lines: ${err}")
