# examples/post_process headless: the engine's G-buffer through AO, indirect light and compose
# into its own framebuffer, three frames; the example itself fails if any item of the engine's
# GL state differs after Obscura's calls. The picture has the scene in it: not black on
# average (mean above 0.05 of the range) and not one flat colour (standard deviation above
# 0.01).
file(REMOVE_RECURSE "${WORK_DIR}")
file(MAKE_DIRECTORY "${WORK_DIR}")
foreach(scene cornell /usr/share/assimp/models/PLY/Wuson.ply)
  get_filename_component(stem "${scene}" NAME_WE)
  set(picture "${WORK_DIR}/${stem}.png")
  execute_process(COMMAND "${EXAMPLE}" --scene "${scene}" --size 96x64 --frames 3 --out "${picture}"
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0 OR NOT out MATCHES "host GL state: ([0-9]+) items as the engine left them, in each of 3 frames")
    message(FATAL_ERROR "post_process on ${scene} failed (${rc}):\n${out}${err}")
  endif()
  if(CMAKE_MATCH_1 LESS 20)
    message(FATAL_ERROR "post_process checked only ${CMAKE_MATCH_1} items of the engine's state")
  endif()
  execute_process(COMMAND "${OIIOTOOL}" --stats "${picture}" OUTPUT_VARIABLE stats ERROR_VARIABLE err)
  if(NOT stats MATCHES "Stats Avg: ([0-9.]+) ([0-9.]+) ([0-9.]+)")
    message(FATAL_ERROR "no statistics for ${picture}: ${stats}${err}")
  endif()
  if(NOT CMAKE_MATCH_1 GREATER 0.05 OR NOT stats MATCHES "Stats StdDev: ([0-9.]+)" OR NOT CMAKE_MATCH_1 GREATER 0.01)
    message(FATAL_ERROR "${picture} is black or flat: ${stats}")
  endif()
endforeach()
