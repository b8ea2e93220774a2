# Runs an app under mpiexec and checks the outcome; used by tests/apps/CMakeLists.txt as
#   cmake -DMPIEXEC=.. -DNP=.. -DAPP=.. -DARGS="a|b|c" [-DEXPECT_FAIL=1 -DMESSAGE=..
#         [-DEXIT_CODE=n] [-DENDS_JOB=1]]
#         [-DSTDOUT_HAS="text|text"] [-DQUIET_STDOUT=1] [-DJSON=file -DJSON_EXPECT="k=v|k=v"
#         -DPYTHON=python3 -DCHECK_SUMMARY=check_summary.py]
#         [-DDUMP=file -DDUMP_HEADER=line [-DDUMP_LINES=n]]
#         -P RunAppCheck.cmake
# A failing run must exit non-zero (EXIT_CODE exactly, if given), print MESSAGE exactly once
# on stderr (one rank reports, not every rank) and no sign of a crash or an abort (ENDS_JOB:
# an input error that one rank finds alone mid-step, core::RankInputError, which ends the job
# with MPI_Abort and the input error's code; MPI_ABORT's notice is then expected). A
# successful run must exit 0.
cmake_minimum_required(VERSION 3.25)

function(fail what)
  message(FATAL_ERROR "${what}\n--- exit code: ${rc}\n--- stdout:\n${out}\n--- stderr:\n${err}")
endfunction()

function(count_occurrences haystack needle result)
  set(n 0)
  string(LENGTH "${needle}" len)
  while(TRUE)
    string(FIND "${haystack}" "${needle}" pos)
    if(pos EQUAL -1)
      break()
    endif()
    math(EXPR n "${n} + 1")
    math(EXPR next "${pos} + ${len}")
    string(SUBSTRING "${haystack}" ${next} -1 haystack)
  endwhile()
  set(${result} ${n} PARENT_SCOPE)
endfunction()

string(REPLACE "|" ";" args "${ARGS}")
foreach(f IN ITEMS JSON DUMP)
  if(${f})
    file(REMOVE "${${f}}")
  endif()
endforeach()

execute_process(
  COMMAND ${MPIEXEC} -n ${NP} --oversubscribe ${APP} ${args}
  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err TIMEOUT 60)

set(crashes "internal error" "terminate called" "Segmentation fault" "MPI_ABORT" "Aborted"
            "core dumped" "Sanitizer" "runtime error:")
if(ENDS_JOB)
  list(REMOVE_ITEM crashes "MPI_ABORT")
endif()
foreach(crash IN LISTS crashes)
  string(FIND "${err}" "${crash}" pos)
  if(NOT pos EQUAL -1)
    fail("the run crashed or aborted ('${crash}' on stderr)")
  endif()
endforeach()

if(EXPECT_FAIL)
  if(NOT rc MATCHES "^[0-9]+$")
    fail("the run did not exit normally: ${rc}")
  endif()
  if(rc EQUAL 0)
    fail("expected a non-zero exit code")
  endif()
  if(DEFINED EXIT_CODE AND NOT rc EQUAL EXIT_CODE)
    fail("expected exit code ${EXIT_CODE}")
  endif()
  count_occurrences("${err}" "${MESSAGE}" n)
  if(NOT n EQUAL 1)
    fail("expected the message exactly once on stderr, found it ${n} times:\n  ${MESSAGE}")
  endif()
  return()
endif()

if(NOT rc STREQUAL "0")
  fail("expected exit code 0")
endif()
if(STDOUT_HAS)
  string(REPLACE "|" ";" texts "${STDOUT_HAS}")
  foreach(text IN LISTS texts)
    string(FIND "${out}" "${text}" pos)
    if(pos EQUAL -1)
      fail("expected on stdout: ${text}")
    endif()
  endforeach()
endif()
if(QUIET_STDOUT AND NOT out STREQUAL "")
  fail("expected no output on stdout with --quiet")
endif()
if(JSON)
  if(NOT EXISTS "${JSON}")
    fail("the summary ${JSON} was not written")
  endif()
  string(REPLACE "|" ";" expectations "${JSON_EXPECT}")
  if(PYTHON)
    execute_process(COMMAND ${PYTHON} ${CHECK_SUMMARY} ${JSON} ${expectations}
                    RESULT_VARIABLE prc OUTPUT_VARIABLE pout ERROR_VARIABLE perr)
    if(NOT prc STREQUAL "0")
      fail("summary check failed: ${pout}${perr}")
    endif()
  else()
    file(READ "${JSON}" text) # no Python: at least check that it is JSON with the keys
    foreach(key IN ITEMS scene ranks blocks sync particles shadows steps wall_s pupcs
                         peak_rss_bytes timing_s comm conserved checksum)
      string(JSON value ERROR_VARIABLE jerr GET "${text}" ${key})
      if(jerr)
        fail("summary: ${jerr}")
      endif()
    endforeach()
  endif()
endif()
if(DUMP)
  if(NOT EXISTS "${DUMP}")
    fail("the dump ${DUMP} was not written")
  endif()
  file(STRINGS "${DUMP}" dump_lines)
  list(GET dump_lines 0 header)
  if(NOT header STREQUAL "${DUMP_HEADER}")
    fail("the dump's first line is '${header}', expected '${DUMP_HEADER}'")
  endif()
  list(LENGTH dump_lines n)
  if(DUMP_LINES AND NOT n EQUAL DUMP_LINES)
    fail("the dump has ${n} lines, expected ${DUMP_LINES}")
  endif()
endif()
