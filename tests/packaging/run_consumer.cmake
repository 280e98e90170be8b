# Builds and runs tests/packaging/consumer against this build of Obscura.
#   MODE=find_package:      install BUILD_DIR into WORK_DIR/prefix, then find_package() it
#   MODE=add_subdirectory:  build Obscura from SOURCE_DIR inside the consumer (BUILD_SHARED_LIBS=SHARED)
#   MODE=find_package_other_kind: build and install Obscura alone with BUILD_SHARED_LIBS=SHARED,
#                           then find_package() it
file(REMOVE_RECURSE "${WORK_DIR}")
file(MAKE_DIRECTORY "${WORK_DIR}")

function(run)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "failed (${rc}): ${ARGN}\n${out}\n${err}")
  endif()
  message(STATUS "${out}")
endfunction()

include(ProcessorCount)
ProcessorCount(jobs)
set(consumer_src "${SOURCE_DIR}/tests/packaging/consumer")
if(MODE STREQUAL "find_package")
  run("${CMAKE_COMMAND}" --install "${BUILD_DIR}" --prefix "${WORK_DIR}/prefix")
  set(configure_args "-DCMAKE_PREFIX_PATH=${WORK_DIR}/prefix")
elseif(MODE STREQUAL "find_package_other_kind")
  # The library alone (core + headless), of the other kind, built and installed on its own.
  run("${CMAKE_COMMAND}" -S "${SOURCE_DIR}" -B "${WORK_DIR}/obscura" -G "${GENERATOR}" -DCMAKE_BUILD_TYPE=Release
      "-DBUILD_SHARED_LIBS=${SHARED}" -DOBSCURA_BUILD_TESTS=OFF -DOBSCURA_BUILD_EXAMPLES=OFF -DOBSCURA_BUILD_CLI=OFF
      -DOBSCURA_BUILD_ASSETS=OFF)
  run("${CMAKE_COMMAND}" --build "${WORK_DIR}/obscura" --parallel ${jobs})
  run("${CMAKE_COMMAND}" --install "${WORK_DIR}/obscura" --prefix "${WORK_DIR}/prefix")
  set(configure_args "-DCMAKE_PREFIX_PATH=${WORK_DIR}/prefix")
else()
  # Only what the consumer uses: the core and obscura::headless (no assimp/OpenImageIO).
  set(configure_args "-DOBSCURA_SOURCE_DIR=${SOURCE_DIR}" "-DBUILD_SHARED_LIBS=${SHARED}" -DOBSCURA_BUILD_ASSETS=OFF)
endif()
run("${CMAKE_COMMAND}" -S "${consumer_src}" -B "${WORK_DIR}/build" -G "${GENERATOR}" -DCMAKE_BUILD_TYPE=Release
    ${configure_args})
run("${CMAKE_COMMAND}" --build "${WORK_DIR}/build" --parallel ${jobs})
run("${WORK_DIR}/build/consumer")
