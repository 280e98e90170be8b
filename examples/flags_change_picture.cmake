# The integrator examples' flags reach the integrator: each pair of argument lists, differing
# in one flag, must give different headless pictures (a flag that is parsed but not passed on
# would give the same one). PAIRS: pairs separated by '|', the two sides of a pair by '~'.
file(REMOVE_RECURSE "${WORK_DIR}")
file(MAKE_DIRECTORY "${WORK_DIR}")
string(REPLACE "|" ";" pairs "${PAIRS}")
set(index 0)
foreach(pair IN LISTS pairs)
  math(EXPR index "${index} + 1")
  string(REPLACE "~" ";" sides "${pair}")
  set(pictures "")
  foreach(side a b)
    list(POP_FRONT sides case)
    separate_arguments(args UNIX_COMMAND "${case}")
    set(picture "${WORK_DIR}/${index}_${side}.png")
    execute_process(COMMAND "${EXAMPLE}" --size 64x48 ${args} --out "${picture}" RESULT_VARIABLE rc OUTPUT_VARIABLE out
                    ERROR_VARIABLE err)
    if(NOT rc EQUAL 0)
      message(FATAL_ERROR "headless run (${case}) failed:\n${out}${err}")
    endif()
    list(APPEND pictures "${picture}")
  endforeach()
  # idiff exits 0 only when the pictures match within -fail 0 (any difference fails).
  execute_process(COMMAND "${IDIFF}" -fail 0 -warn 0 ${pictures} RESULT_VARIABLE rc OUTPUT_VARIABLE out)
  if(rc EQUAL 0)
    message(FATAL_ERROR "'${pair}': the two flags gave the same picture:\n${out}")
  endif()
endforeach()
