# Renders the same output headless (EGL) and in a GLFW window under Xvfb (GLX), reading the
# window back from its framebuffer, and requires identical pictures.
file(REMOVE_RECURSE "${WORK_DIR}")
file(MAKE_DIRECTORY "${WORK_DIR}")
foreach(output direct normal)
  execute_process(COMMAND "${EXAMPLE}" --size 96x64 --output ${output} --out "${WORK_DIR}/headless_${output}.png"
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "headless run failed:\n${out}${err}")
  endif()
  execute_process(COMMAND "${XVFB_RUN}" -a -s "-screen 0 640x480x24" "${EXAMPLE}" --window --frames 3 --size 96x64
                          --output ${output} --out "${WORK_DIR}/window_${output}.png"
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "window run failed:\n${out}${err}")
  endif()
  message(STATUS "${out}")
  execute_process(COMMAND "${IDIFF}" -fail 0 -failpercent 0 "${WORK_DIR}/headless_${output}.png" "${WORK_DIR}/window_${output}.png"
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "window and headless pictures of '${output}' differ:\n${out}${err}")
  endif()
endforeach()
