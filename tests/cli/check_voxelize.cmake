# `obscura voxelize` end to end: the files of the design map (grid.json + grid.u8, x fastest)
# and the optional PLY, in both modes; bad options are refused clearly.
file(REMOVE_RECURSE "${WORK_DIR}")
include("${CMAKE_CURRENT_LIST_DIR}/run.cmake")

run("${OBSCURA}" voxelize --scene cornell --res 32 --slices 256 --mode surface --out "${WORK_DIR}/surface" --ply --frames 1)
run("${PYTHON}" "${SOURCE_DIR}/tests/cli/check_voxel_grid.py" "${WORK_DIR}/surface" --cornell)
run("${OBSCURA}" voxelize --scene /usr/share/assimp/models/PLY/Wuson.ply --res 16 --mode solid --out "${WORK_DIR}/solid" --frames 1)
run("${PYTHON}" "${SOURCE_DIR}/tests/cli/check_voxel_grid.py" "${WORK_DIR}/solid")

foreach(bad "--res;48" "--slices;200" "--mode;hollow")
  execute_process(COMMAND "${OBSCURA}" voxelize --scene cornell ${bad} --out "${WORK_DIR}/bad"
                  RESULT_VARIABLE rc ERROR_VARIABLE err OUTPUT_QUIET)
  list(GET bad 0 option)
  if(rc EQUAL 0 OR NOT err MATCHES "${option}|resolution")
    message(FATAL_ERROR "voxelize ${bad} was not refused clearly: ${err}")
  endif()
endforeach()
