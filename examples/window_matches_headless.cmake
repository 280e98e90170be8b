# Renders the same picture headless (EGL) and in a GLFW window under Xvfb (GLX), reading the
# window back from its framebuffer, and requires identical pictures that are not blank: the
# headless picture's colour channels must span at least a tenth of their range (an empty or
# uniform picture would otherwise pass). CASES: the example's arguments per case, cases
# separated by '|'.
file(REMOVE_RECURSE "${WORK_DIR}")
file(MAKE_DIRECTORY "${WORK_DIR}")
string(REPLACE "|" ";" cases "${CASES}")
set(index 0)
foreach(case IN LISTS cases)
  separate_arguments(args UNIX_COMMAND "${case}")
  math(EXPR index "${index} + 1")
  execute_process(COMMAND "${EXAMPLE}" --size 96x64 ${args} --out "${WORK_DIR}/headless_${index}.png"
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "headless run (${case}) failed:\n${out}${err}")
  endif()
  execute_process(COMMAND "${OIIOTOOL}" "${WORK_DIR}/headless_${index}.png" --printstats OUTPUT_VARIABLE stats
                  RESULT_VARIABLE rc)
  string(REGEX MATCH "Stats Min: ([0-9]+) ([0-9]+) ([0-9]+)" min_line "${stats}")
  set(lows "${CMAKE_MATCH_1};${CMAKE_MATCH_2};${CMAKE_MATCH_3}")
  string(REGEX MATCH "Stats Max: ([0-9]+) ([0-9]+) ([0-9]+)" max_line "${stats}")
  set(highs "${CMAKE_MATCH_1};${CMAKE_MATCH_2};${CMAKE_MATCH_3}")
  if(NOT rc EQUAL 0 OR NOT min_line OR NOT max_line)
    message(FATAL_ERROR "no statistics for the headless picture of '${case}':\n${stats}")
  endif()
  set(widest 0)
  foreach(channel 0 1 2)
    list(GET lows ${channel} low)
    list(GET highs ${channel} high)
    math(EXPR span "${high} - ${low}")
    if(span GREATER widest)
      set(widest ${span})
    endif()
  endforeach()
  if(widest LESS 26)
    message(FATAL_ERROR "the headless picture of '${case}' is blank: its channels span ${widest} of 255")
  endif()
  execute_process(COMMAND "${XVFB_RUN}" -a -s "-screen 0 640x480x24" "${EXAMPLE}" --window --frames 3 --size 96x64
                          ${args} --out "${WORK_DIR}/window_${index}.png"
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "window run (${case}) failed:\n${out}${err}")
  endif()
  message(STATUS "${out}")
  execute_process(COMMAND "${IDIFF}" -fail 0 -failpercent 0 "${WORK_DIR}/headless_${index}.png" "${WORK_DIR}/window_${index}.png"
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "window and headless pictures of '${case}' differ:\n${out}${err}")
  endif()
endforeach()
