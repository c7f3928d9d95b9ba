# Every command the documentation shows as runnable runs and exits 0: the lines starting `build/hubbeam` in the
# ```sh blocks of README.md and docs/cli.md (a line ending in \ continues), in page order, each through sh from
# a fresh folder that holds `build` (this build) and `cases` (the scenes), so their files land there and a later
# command can read an earlier one's. Then README's ```python blocks, each in its own process, when a Python
# interpreter is given. Every
# command of `hubbeam --help` must be shown at least once, but sweep (it needs a sweep file and a Dask cluster:
# tests/python runs it) and stress (its quick subset is the test cli_stress_quick, 15 s).
# Run as cmake -DSRC=source-dir -DBUILD=build-dir -DWORK=scratch-dir [-DPYTHON=python3 -DPYTHONPATH=dir]
#   -P docs_commands.cmake.
cmake_policy(SET CMP0057 NEW)  # if(IN_LIST)

file(REMOVE_RECURSE ${WORK})
file(MAKE_DIRECTORY ${WORK})
file(CREATE_LINK ${BUILD} ${WORK}/build SYMBOLIC)
file(CREATE_LINK ${SRC}/cases ${WORK}/cases SYMBOLIC)

# The lines of a page's blocks fenced as LANG, in order, continuation lines joined; [, ] and ; stand as @LB@,
# @RB@ and @SC@ (in a CMake list they would join or split items).
function(block_lines page lang out)
  file(READ ${page} text)
  string(REPLACE "[" "@LB@" text "${text}")
  string(REPLACE "]" "@RB@" text "${text}")
  string(REPLACE ";" "@SC@" text "${text}")
  string(REPLACE "\n" ";" lines "${text}")
  set(result "")
  set(inside OFF)
  set(pending "")
  foreach(line IN LISTS lines)
    if(line MATCHES "^```")
      if(inside)
        set(inside OFF)
      elseif(line STREQUAL "```${lang}")
        set(inside ON)
      endif()
      continue()
    endif()
    if(NOT inside)
      continue()
    endif()
    string(APPEND pending "${line}")
    if(pending MATCHES "\\\\$")
      string(REGEX REPLACE "\\\\$" " " pending "${pending}")
      continue()
    endif()
    list(APPEND result "${pending}")
    set(pending "")
  endforeach()
  set(${out} "${result}" PARENT_SCOPE)
endfunction()

set(shown_commands "")
set(count 0)
foreach(page ${SRC}/README.md ${SRC}/docs/cli.md)
  block_lines(${page} sh lines)
  foreach(line IN LISTS lines)
    string(STRIP "${line}" line)
    if(NOT line MATCHES "^build/hubbeam")
      continue()
    endif()
    string(REGEX REPLACE " +#.*" "" line "${line}")  # a trailing comment
    string(REPLACE "@LB@" "[" line "${line}")
    string(REPLACE "@RB@" "]" line "${line}")
    string(REPLACE "@SC@" ";" line "${line}")
    if(line MATCHES "^build/hubbeam ([a-z]+)")
      list(APPEND shown_commands ${CMAKE_MATCH_1})
    endif()
    execute_process(COMMAND sh -c "${line}" WORKING_DIRECTORY ${WORK}
                    RESULT_VARIABLE code OUTPUT_VARIABLE out ERROR_VARIABLE err)
    if(NOT code EQUAL 0)
      message(FATAL_ERROR "${page}: `${line}` exited ${code}\nstdout:\n${out}\nstderr:\n${err}")
    endif()
    math(EXPR count "${count} + 1")
  endforeach()
endforeach()

execute_process(COMMAND ${BUILD}/hubbeam --help OUTPUT_VARIABLE top)
string(REGEX REPLACE ".*\nSubcommands:\n" "" listing "${top}")
string(REGEX MATCHALL "\n  [a-z]+ " words "\n${listing}")
foreach(w IN LISTS words)
  string(STRIP "${w}" w)
  if(NOT w STREQUAL "sweep" AND NOT w STREQUAL "stress" AND NOT w IN_LIST shown_commands)
    message(FATAL_ERROR "hubbeam ${w}: no runnable example in README.md or docs/cli.md")
  endif()
endforeach()

set(python_ran "")
if(PYTHON)
  file(READ ${SRC}/README.md readme)
  string(REPLACE ";" "@SC@" readme "${readme}")  # a ; would split the list of blocks
  string(REGEX MATCHALL "```python\n[^`]*```" blocks "${readme}")
  if(NOT blocks)
    message(FATAL_ERROR "README.md has no ```python block")
  endif()
  # Each block in a Python of its own, in page order, from the same folder: a later block is a new session that
  # reads what an earlier one saved.
  foreach(block IN LISTS blocks)
    string(REPLACE "@SC@" ";" block "${block}")
    string(REGEX REPLACE "^```python\n" "" block "${block}")
    string(REGEX REPLACE "```$" "" block "${block}")
    execute_process(COMMAND ${CMAKE_COMMAND} -E env PYTHONPATH=${PYTHONPATH} MPLBACKEND=Agg ${PYTHON} -c "${block}"
                    WORKING_DIRECTORY ${WORK} RESULT_VARIABLE code OUTPUT_VARIABLE out ERROR_VARIABLE err)
    if(NOT code EQUAL 0)
      message(FATAL_ERROR "README.md's Python example exited ${code}\n${block}\nstderr:\n${err}")
    endif()
  endforeach()
  set(python_ran " and README's Python example")
endif()
message(STATUS "${count} documented commands${python_ran} ran and exited 0")
