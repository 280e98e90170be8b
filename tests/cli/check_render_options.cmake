# `obscura render`'s per-frame options: a camera given without planes gets planes fitted to the
# scene, and temporal accumulation over the rendered frames.
file(REMOVE_RECURSE "${WORK_DIR}")
file(MAKE_DIRECTORY "${WORK_DIR}")

include("${CMAKE_CURRENT_LIST_DIR}/run.cmake")

# A close-up camera on a mesh file (a floor and a wall, 4 units wide, framed from 8.6 units
# with its near plane at 4.1) 3 units before the wall, where every part of the model is nearer
# than that near plane: the planes are fitted to the model seen from the given eye,
# so its AO image has geometry (AO below 1 at the crease); turned away from the model the
# command still renders, and says that the image holds no geometry.
file(WRITE "${WORK_DIR}/floor_wall.obj" "v -2 0 -2\nv 2 0 -2\nv 2 0 2\nv -2 0 2\nv -2 2 -2\nv 2 2 -2\n"
                                        "f 1 4 3\nf 1 3 2\nf 1 2 6\nf 1 6 5\n")
execute_process(COMMAND "${OBSCURA}" render --scene "${WORK_DIR}/floor_wall.obj" --size 32x24 --technique ao.raymarch
                        --set radius=1 --output ao --out "${WORK_DIR}/close.exr" --camera 0,1,1,0,0.5,-2,0,1,0,60
                RESULT_VARIABLE rc ERROR_VARIABLE err OUTPUT_QUIET)
execute_process(COMMAND "${OIIOTOOL}" --stats "${WORK_DIR}/close.exr" OUTPUT_VARIABLE info ERROR_VARIABLE oerr)
if(NOT rc EQUAL 0 OR err MATCHES "warning" OR NOT info MATCHES "Stats Min: ([-0-9.e+]+)" OR NOT CMAKE_MATCH_1 LESS 0.9)
  message(FATAL_ERROR "close-up camera: rc ${rc}, ${err}, AO ${info}${oerr}")
endif()
execute_process(COMMAND "${OBSCURA}" render --scene "${WORK_DIR}/floor_wall.obj" --size 32x24 --technique ao.raymarch
                        --set radius=1 --output ao --out "${WORK_DIR}/away.exr" --camera 0,1,3,0,1,10,0,1,0,60
                RESULT_VARIABLE rc ERROR_VARIABLE err OUTPUT_QUIET)
if(NOT rc EQUAL 0 OR NOT err MATCHES "warning: the whole scene lies outside the camera's view")
  message(FATAL_ERROR "a camera turned away from the scene gave no warning: rc ${rc}, ${err}")
endif()
refused("near and far must satisfy" "${OBSCURA}" render --scene "${WORK_DIR}/floor_wall.obj" --size 8x8
        --technique gbuffer --out "${WORK_DIR}/x.exr" --camera 0,1,1,0,0.5,-2,0,1,0,60,5,1)

# Temporal accumulation over the rendered frames: 8 frames with temporal=1 (the frame index
# counted up each frame) give another AO image than 1 frame; without it every frame is the
# same, as the bench measures it.
foreach(case "1;0" "8;0" "8;1")
  list(GET case 0 frames)
  list(GET case 1 temporal)
  run("${OBSCURA}" render --scene cornell --size 32x24 --technique ao.raymarch --set rays=4 --set temporal=${temporal}
      --frames ${frames} --output ao --out "${WORK_DIR}/temporal_${frames}_${temporal}.exr")
endforeach()
foreach(pair "8_0;1_0;0" "8_1;1_0;1")
  list(GET pair 0 a)
  list(GET pair 1 b)
  list(GET pair 2 differ)
  execute_process(COMMAND "${IDIFF}" -fail 0 -warn 0 "${WORK_DIR}/temporal_${a}.exr" "${WORK_DIR}/temporal_${b}.exr"
                  RESULT_VARIABLE rc OUTPUT_QUIET ERROR_QUIET)
  if((differ AND rc EQUAL 0) OR (NOT differ AND NOT rc EQUAL 0))
    message(FATAL_ERROR "temporal ${a} against ${b}: idiff exit ${rc}, expected them to differ: ${differ}")
  endif()
endforeach()
refused("frame_index=1.5.*whole number"
        "${OBSCURA}" render --scene cornell --size 8x8 --technique ao.raymarch --set frame_index=1.5 --out "${WORK_DIR}/x.exr")
