# Builds and runs tests/packaging/consumer against this build of Obscura.
#   MODE=find_package:      install BUILD_DIR into WORK_DIR/prefix, then find_package() it
#   MODE=add_subdirectory:  build Obscura from SOURCE_DIR inside the consumer (BUILD_SHARED_LIBS=SHARED)
file(REMOVE_RECURSE "${WORK_DIR}")
file(MAKE_DIRECTORY "${WORK_DIR}")

function(run)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "failed (${rc}): ${ARGN}\n${out}\n${err}")
  endif()
  message(STATUS "${out}")
endfunction()

set(consumer_src "${SOURCE_DIR}/tests/packaging/consumer")
if(MODE STREQUAL "find_package")
  run("${CMAKE_COMMAND}" --install "${BUILD_DIR}" --prefix "${WORK_DIR}/prefix")
  set(configure_args "-DCMAKE_PREFIX_PATH=${WORK_DIR}/prefix")
else()
  # Only what the consumer uses: the core and obscura::headless (no assimp/OpenImageIO).
  set(configure_args "-DOBSCURA_SOURCE_DIR=${SOURCE_DIR}" "-DBUILD_SHARED_LIBS=${SHARED}" -DOBSCURA_BUILD_ASSETS=OFF)
endif()
run("${CMAKE_COMMAND}" -S "${consumer_src}" -B "${WORK_DIR}/build" -G "${GENERATOR}" -DCMAKE_BUILD_TYPE=Release
    ${configure_args})
include(ProcessorCount)
ProcessorCount(jobs)
run("${CMAKE_COMMAND}" --build "${WORK_DIR}/build" --parallel ${jobs})
run("${WORK_DIR}/build/consumer")
