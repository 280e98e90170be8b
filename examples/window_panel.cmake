# The ImGui panel in window mode (GLFW on Xvfb): the frame as the window shows it
# (--screenshot) must differ from the headless picture over the panel's title bar and equal
# it right of and below the panel (its place and size are fixed: position (8, 8), ImGui's
# built-in font, at most 300 x 370 pixels with the widgets of both examples).
file(REMOVE_RECURSE "${WORK_DIR}")
file(MAKE_DIRECTORY "${WORK_DIR}")
set(size --size 480x400 --rays 8)
execute_process(COMMAND "${EXAMPLE}" ${size} --out "${WORK_DIR}/headless.png" RESULT_VARIABLE rc ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "headless run failed:\n${err}")
endif()
execute_process(COMMAND "${XVFB_RUN}" -a -s "-screen 0 640x480x24" "${EXAMPLE}" --window --frames 3 ${size}
                        --screenshot "${WORK_DIR}/screen.png"
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "window run failed:\n${out}${err}")
endif()
# region name, oiiotool geometry WxH+X+Y, whether the two pictures must be equal there
foreach(region "title;280x14+12+10;differ" "right;150x400+330+0;equal" "below;480x20+0+380;equal")
  list(GET region 0 name)
  list(GET region 1 geometry)
  list(GET region 2 expect)
  foreach(image headless screen)
    execute_process(COMMAND "${OIIOTOOL}" "${WORK_DIR}/${image}.png" --cut ${geometry} -o "${WORK_DIR}/${image}_${name}.png"
                    RESULT_VARIABLE rc ERROR_VARIABLE err)
    if(NOT rc EQUAL 0)
      message(FATAL_ERROR "oiiotool --cut ${geometry} failed:\n${err}")
    endif()
  endforeach()
  execute_process(COMMAND "${IDIFF}" -fail 0 -failpercent 0 "${WORK_DIR}/headless_${name}.png" "${WORK_DIR}/screen_${name}.png"
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(expect STREQUAL "equal" AND NOT rc EQUAL 0)
    message(FATAL_ERROR "the window differs from the headless picture ${name} the panel:\n${out}${err}")
  elseif(expect STREQUAL "differ" AND rc EQUAL 0)
    message(FATAL_ERROR "no panel drawn: the window equals the headless picture over the panel's ${name}")
  endif()
endforeach()
