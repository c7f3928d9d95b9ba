# The on-demand cache's safety end to end (docs/security.md, "The on-demand cache"): hubbeam loads no object another
# user could have written, checks every object against the checksum recorded when it was compiled, and a stopped
# or hung compilation leaves neither processes nor work folders behind.
#   -DCASE=name -DHUBBEAM=exe -DGEN=hubbeam-gen -DCXX=compiler -DSCENE=scene.toml -DWORK=folder (emptied first)
# Cases: foreign_owner, group_writable, no_home, symlinked_object, truncated_object, old_abi, timeout,
#        killed_compile, untrusted_generator.
file(REMOVE_RECURSE ${WORK})
file(MAKE_DIRECTORY ${WORK})
set(CACHE_DIR ${WORK}/cache)
# A variant that is not built in, small enough to compile in seconds.
set(VARIANT amm_nx1_ny3_prescribed_first)
set(RUN run ${SCENE} --method amm --nx 1 --ny 3 --t-end 0.2 -o ${WORK}/out.csv)
set(MARK ${WORK}/planted-code-ran)

# hubbeam with env (a list of VAR=value and --unset=VAR) and arguments; sets code, out, err.
macro(hubbeam env)
  execute_process(COMMAND ${CMAKE_COMMAND} -E env ${env} ${HUBBEAM} ${ARGN}
                  RESULT_VARIABLE code OUTPUT_VARIABLE out ERROR_VARIABLE err TIMEOUT 300)
endmacro()

function(expect_refusal what regex)
  if(NOT code STREQUAL "2")
    message(FATAL_ERROR "${what}: expected exit 2, got '${code}': ${out}${err}")
  endif()
  # (The note that a compilation starts may come first; the refusal is one line of its own.)
  string(REGEX REPLACE "^hubbeam: compiling variant [^\n]* \\(once per machine\\)\n" "" err "${err}")
  string(REGEX MATCHALL "\n" lines "${err}")
  list(LENGTH lines n)
  if(NOT err MATCHES "${regex}" OR NOT n EQUAL 1)
    message(FATAL_ERROR "${what}: expected one line matching '${regex}', got: ${err}")
  endif()
  if(EXISTS ${MARK})
    message(FATAL_ERROR "${what}: the planted object's code ran")
  endif()
endfunction()

# This hubbeam's cache folder for a root (the generator's version is part of its name).
function(version_dir root var)
  hubbeam("HUBBEAM_CACHE_DIR=${root}" variants)
  if(NOT out MATCHES "cache: ([^\n]*) \\(clear")
    message(FATAL_ERROR "hubbeam variants did not name its cache: ${out}${err}")
  endif()
  set(${var} ${CMAKE_MATCH_1} PARENT_SCOPE)
endfunction()

# An object that would run code when loaded (a constructor writing MARK) and otherwise looks like VARIANT, with
# a checksum record that matches it: only the folder's owner or mode can give it away.
function(plant dir)
  file(MAKE_DIRECTORY ${dir})
  file(WRITE ${WORK}/planted.cpp "#include <cstdio>
__attribute__((constructor)) static void mark() { if (FILE* f = std::fopen(\"${MARK}\", \"w\")) std::fclose(f); }
extern \"C\" __attribute__((visibility(\"default\"))) const void* hubbeam_variant() { return nullptr; }
")
  execute_process(COMMAND ${CXX} -shared -fPIC ${WORK}/planted.cpp -o ${dir}/${VARIANT}.so RESULT_VARIABLE c
                  ERROR_VARIABLE e)
  if(NOT c EQUAL 0)
    message(FATAL_ERROR "cannot build the planted object: ${e}")
  endif()
  file(SHA256 ${dir}/${VARIANT}.so sum)
  file(SIZE ${dir}/${VARIANT}.so size)
  file(WRITE ${dir}/${VARIANT}.so.sha256 "sha256 ${sum} size ${size}\n")
endfunction()

function(chmod mode path)
  execute_process(COMMAND chmod ${mode} ${path})
endfunction()

# The work folders a compilation of VARIANT left in dir.
function(work_folders dir var)
  file(GLOB left LIST_DIRECTORIES true ${dir}/.${VARIANT}.work-*)
  set(${var} "${left}" PARENT_SCOPE)
endfunction()

# Whether process pid is alive (a zombie counts as gone).
function(alive pid var)
  execute_process(COMMAND sh -c "ps -o stat= -p ${pid} | grep -qv Z" RESULT_VARIABLE c)
  if(c EQUAL 0)
    set(${var} TRUE PARENT_SCOPE)
  else()
    set(${var} FALSE PARENT_SCOPE)
  endif()
endfunction()

# A stand-in generator that records its process id, then hangs.
set(SLEEPER ${WORK}/hung-gen.sh)
file(WRITE ${SLEEPER} "#!/bin/sh\necho $$ > ${WORK}/gen.pid\nexec sleep 120\n")
chmod(755 ${SLEEPER})

if(CASE STREQUAL "foreign_owner")
  # Another user's cache folder, holding an object of theirs: refused before anything of it is loaded.
  execute_process(COMMAND id -u OUTPUT_VARIABLE uid OUTPUT_STRIP_TRAILING_WHITESPACE)
  if(NOT uid EQUAL 0)
    message(STATUS "skipped: giving a folder to another user needs root")
    return()
  endif()
  version_dir(${CACHE_DIR} dir)
  plant(${dir})
  execute_process(COMMAND chown -R nobody ${CACHE_DIR})
  chmod(755 ${CACHE_DIR})
  hubbeam("HUBBEAM_CACHE_DIR=${CACHE_DIR}" ${RUN})
  expect_refusal("a cache folder of user nobody"
                 "^hubbeam: the variant cache folder ${CACHE_DIR} belongs to nobody, uid [0-9]+, not to you .*HUBBEAM_CACHE_DIR")
  # The same with the default location: XDG_CACHE_HOME's hubbeam folder.
  file(RENAME ${CACHE_DIR} ${WORK}/hubbeam)
  hubbeam("--unset=HUBBEAM_CACHE_DIR;XDG_CACHE_HOME=${WORK}" ${RUN})
  expect_refusal("XDG_CACHE_HOME's cache of user nobody" "^hubbeam: the variant cache folder ${WORK}/hubbeam belongs to nobody")

elseif(CASE STREQUAL "group_writable")
  # A cache folder of ours that others may write to: refused, with the chmod that fixes it.
  version_dir(${CACHE_DIR} dir)
  plant(${dir})
  chmod(775 ${CACHE_DIR})
  hubbeam("HUBBEAM_CACHE_DIR=${CACHE_DIR}" ${RUN})
  expect_refusal("a group-writable HUBBEAM_CACHE_DIR"
                 "^hubbeam: the variant cache folder ${CACHE_DIR} is writable by other users \\(mode 0775\\): run chmod go-w ${CACHE_DIR}")
  # The folder of this version, and the object itself, the same.
  chmod(700 ${CACHE_DIR})
  chmod(777 ${dir})
  hubbeam("HUBBEAM_CACHE_DIR=${CACHE_DIR}" ${RUN})
  expect_refusal("a world-writable version folder" "^hubbeam: the variant cache folder ${dir} is writable by other users")
  chmod(700 ${dir})
  chmod(666 ${dir}/${VARIANT}.so)
  hubbeam("HUBBEAM_CACHE_DIR=${CACHE_DIR}" ${RUN})
  expect_refusal("a world-writable object" "^hubbeam: the cached object ${dir}/${VARIANT}.so is writable by other users")

elseif(CASE STREQUAL "no_home")
  # Without HOME and XDG_CACHE_HOME there is no private place: refused, never a shared temporary folder.
  file(MAKE_DIRECTORY ${WORK}/tmp)
  hubbeam("--unset=HOME;--unset=XDG_CACHE_HOME;--unset=HUBBEAM_CACHE_DIR;TMPDIR=${WORK}/tmp" ${RUN})
  expect_refusal("no HOME" "^hubbeam: no folder for the variant cache: set HUBBEAM_CACHE_DIR \\(or HOME\\)")
  file(GLOB left ${WORK}/tmp/*)
  if(left)
    message(FATAL_ERROR "no HOME: hubbeam wrote into the temporary folder: ${left}")
  endif()
  # A built-in variant needs no cache and still runs.
  hubbeam("--unset=HOME;--unset=XDG_CACHE_HOME;--unset=HUBBEAM_CACHE_DIR" run ${SCENE} --t-end 0.1 -o ${WORK}/built-in.csv)
  if(NOT code EQUAL 0)
    message(FATAL_ERROR "no HOME: a built-in variant did not run: ${err}")
  endif()

elseif(CASE STREQUAL "symlinked_object")
  # An object in our folder that is a symbolic link (to a planted object elsewhere) is not followed.
  version_dir(${CACHE_DIR} dir)
  plant(${WORK}/elsewhere)
  file(MAKE_DIRECTORY ${dir})
  chmod(700 ${CACHE_DIR})
  chmod(700 ${dir})
  file(CREATE_LINK ${WORK}/elsewhere/${VARIANT}.so ${dir}/${VARIANT}.so SYMBOLIC)
  file(COPY ${WORK}/elsewhere/${VARIANT}.so.sha256 DESTINATION ${dir})
  hubbeam("HUBBEAM_CACHE_DIR=${CACHE_DIR}" ${RUN})
  expect_refusal("a symbolic link as the object" "^hubbeam: the cached object ${dir}/${VARIANT}.so is a symbolic link")

elseif(CASE STREQUAL "truncated_object")
  # An object cut short (a full disk, a killed copy) fails its checksum and is compiled again: no bus error.
  hubbeam("HUBBEAM_CACHE_DIR=${CACHE_DIR}" ${RUN})
  if(NOT code EQUAL 0)
    message(FATAL_ERROR "the first compilation failed: ${err}")
  endif()
  version_dir(${CACHE_DIR} dir)
  file(SIZE ${dir}/${VARIANT}.so size)
  math(EXPR half "${size} / 2")
  execute_process(COMMAND truncate -s ${half} ${dir}/${VARIANT}.so)
  hubbeam("HUBBEAM_CACHE_DIR=${CACHE_DIR}" ${RUN})
  if(NOT code EQUAL 0 OR NOT err MATCHES "${dir}/${VARIANT}.so does not match the checksum recorded when it was compiled \\(cut short or changed\\): compiling it again")
    message(FATAL_ERROR "a truncated object: expected a note and a new compilation, got exit '${code}': ${err}")
  endif()
  file(SIZE ${dir}/${VARIANT}.so again)
  if(NOT again EQUAL size)
    message(FATAL_ERROR "a truncated object: the new object has ${again} bytes, the first ${size}")
  endif()

elseif(CASE STREQUAL "old_abi")
  # An object whose table row carries another interface version is refused before any kernel is called. The
  # stand-in generator is the real one with the version in its output changed.
  # (hubbeam calls: hubbeam-gen --module --quiet --out DIR VARIANT)
  file(WRITE ${WORK}/old-gen.sh "#!/bin/sh\n'${GEN}' \"$@\" || exit $?\n"
             "while [ \"$1\" != --out ]; do shift; done\n"
             "sed -i 's/\\.abi_version = [0-9]*,/.abi_version = 1,/' \"$2\"/*.cpp\n")
  chmod(755 ${WORK}/old-gen.sh)
  hubbeam("HUBBEAM_CACHE_DIR=${CACHE_DIR};HUBBEAM_GEN=${WORK}/old-gen.sh" ${RUN})
  expect_refusal("an object of an older generator"
                 "^hubbeam: [^\n]*/${VARIANT}.so was built by an older generator \\(interface version 1, this hubbeam reads [0-9]+\\): delete ")
  # An object of the layout before rows carried a version (no abi_version field: the row starts with the name's
  # pointer), as the generator of that time made them.
  file(REMOVE_RECURSE ${CACHE_DIR})
  file(WRITE ${WORK}/old-gen.sh "#!/bin/sh\n'${GEN}' \"$@\" || exit $?\n"
             "while [ \"$1\" != --out ]; do shift; done\n"
             "sed -i '/int abi_version;/d' \"$2\"/generated_abi.h\n"
             "sed -i '/\\.abi_version = /d' \"$2\"/*.cpp\n")
  hubbeam("HUBBEAM_CACHE_DIR=${CACHE_DIR};HUBBEAM_GEN=${WORK}/old-gen.sh" ${RUN})
  expect_refusal("an object of the unversioned layout"
                 "^hubbeam: [^\n]*/${VARIANT}.so was built by an older generator \\(one that recorded no interface version")

elseif(CASE STREQUAL "untrusted_generator")
  # $HUBBEAM_GEN passes the checks of the built-in generator: a file others may change, or a symbolic link (whose
  # target whoever may change the link chooses), is never run. The stand-in would leave a mark if it ran.
  file(WRITE ${WORK}/planted-gen.sh "#!/bin/sh\ntouch '${MARK}'\nexec '${GEN}' \"$@\"\n")
  chmod(775 ${WORK}/planted-gen.sh)
  hubbeam("HUBBEAM_CACHE_DIR=${CACHE_DIR};HUBBEAM_GEN=${WORK}/planted-gen.sh" ${RUN} --source generated)
  expect_refusal("a group-writable HUBBEAM_GEN"
                 "HUBBEAM_GEN: ${WORK}/planted-gen.sh is writable by other users: hubbeam runs a generator only if")
  chmod(755 ${WORK}/planted-gen.sh)
  file(CREATE_LINK ${WORK}/planted-gen.sh ${WORK}/linked-gen.sh SYMBOLIC)
  hubbeam("HUBBEAM_CACHE_DIR=${CACHE_DIR};HUBBEAM_GEN=${WORK}/linked-gen.sh" ${RUN} --source generated)
  expect_refusal("a HUBBEAM_GEN that is a symbolic link"
                 "HUBBEAM_GEN: ${WORK}/linked-gen.sh is a symbolic link, which hubbeam does not follow")

elseif(CASE STREQUAL "timeout")
  # A hung generator is stopped at the time limit, with its process group and work folder.
  string(TIMESTAMP start "%s")
  hubbeam("HUBBEAM_CACHE_DIR=${CACHE_DIR};HUBBEAM_GEN=${SLEEPER};HUBBEAM_COMPILE_TIMEOUT=1" ${RUN})
  string(TIMESTAMP end "%s")
  expect_refusal("a hung generator"
                 "^hubbeam: generating ${VARIANT} was stopped after 1 s, the limit for its size: set HUBBEAM_COMPILE_TIMEOUT")
  math(EXPR took "${end} - ${start}")
  if(took GREATER 30)
    message(FATAL_ERROR "a hung generator: hubbeam took ${took} s with a limit of 1 s")
  endif()
  file(READ ${WORK}/gen.pid pid)
  string(STRIP "${pid}" pid)
  alive(${pid} running)
  version_dir(${CACHE_DIR} dir)
  work_folders(${dir} left)
  if(running OR left)
    message(FATAL_ERROR "a hung generator: generator still running (${running}) or work folders left (${left})")
  endif()

elseif(CASE STREQUAL "killed_compile")
  # hubbeam stopped during a compilation, by SIGTERM (it cleans up) and by SIGKILL (its supervisor kills the tools;
  # the next compilation removes the work folder).
  version_dir(${CACHE_DIR} dir)
  foreach(sig TERM KILL)
    file(REMOVE ${WORK}/gen.pid)
    execute_process(COMMAND sh -c "HUBBEAM_CACHE_DIR='${CACHE_DIR}' HUBBEAM_GEN='${SLEEPER}' '${HUBBEAM}' run '${SCENE}' \
                                   --method amm --nx 1 --ny 3 --t-end 0.2 -o '${WORK}/out.csv' 2>'${WORK}/killed.err' & h=$!
                                   i=0; while [ ! -s '${WORK}/gen.pid' ] && [ $i -lt 300 ]; do sleep 0.1; i=$((i+1)); done
                                   kill -${sig} $h; wait $h; echo $?"
                    OUTPUT_VARIABLE status OUTPUT_STRIP_TRAILING_WHITESPACE)
    file(READ ${WORK}/gen.pid pid)
    string(STRIP "${pid}" pid)
    set(running TRUE)
    foreach(i RANGE 300)  # the supervisor's parent-death signal is asynchronous (up to 30 s on a loaded machine)
      alive(${pid} running)
      if(NOT running)
        break()
      endif()
      execute_process(COMMAND sleep 0.1)
    endforeach()
    if(running)
      execute_process(COMMAND kill -9 ${pid})
      message(FATAL_ERROR "SIG${sig} during a compilation: the generator (pid ${pid}) is still running")
    endif()
    work_folders(${dir} left)
    if(sig STREQUAL "TERM" AND left)
      message(FATAL_ERROR "SIGTERM during a compilation left work folders: ${left}")
    endif()
    if(sig STREQUAL "TERM" AND NOT status EQUAL 143)
      message(FATAL_ERROR "SIGTERM during a compilation: expected hubbeam to end by the signal (143), got ${status}")
    endif()
  endforeach()
  # After the SIGKILL: the next compilation of the variant removes what the killed one left.
  hubbeam("HUBBEAM_CACHE_DIR=${CACHE_DIR}" ${RUN})
  work_folders(${dir} left)
  if(NOT code EQUAL 0 OR left)
    message(FATAL_ERROR "after a killed compilation: exit ${code}, work folders left: ${left} ${err}")
  endif()

else()
  message(FATAL_ERROR "unknown CASE '${CASE}'")
endif()
