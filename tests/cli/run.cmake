# run(COMMAND...): runs a command and fails the test with its output unless it succeeds.
function(run)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "failed (${rc}): ${ARGN}\n${out}\n${err}")
  endif()
endfunction()

# refused(PATTERN COMMAND...): fails the test unless the command fails with PATTERN (a regex)
# in its error output, which says why.
function(refused pattern)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc ERROR_VARIABLE err OUTPUT_QUIET)
  if(rc EQUAL 0 OR NOT err MATCHES "${pattern}")
    message(FATAL_ERROR "not refused with '${pattern}': ${ARGN}\n${err}")
  endif()
endfunction()
