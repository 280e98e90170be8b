# Renders the same picture headless (EGL) and in a GLFW window under Xvfb (GLX), reading the
# window back from its framebuffer, and requires identical pictures. CASES: the example's
# arguments per case, cases separated by '|'.
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
