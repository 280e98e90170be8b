# Install rules and the CMake package: find_package(obscura CONFIG [COMPONENTS headless assets]).
# obscura::obscura is always there; obscura::headless and obscura::assets are components,
# each with its own export set so that a consumer of the core needs none of their
# dependencies (EGL, assimp, OpenImageIO, nlohmann-json).
include(CMakePackageConfigHelpers)
set(OBSCURA_CMAKE_DIR "${CMAKE_INSTALL_LIBDIR}/cmake/obscura")

install(DIRECTORY "${PROJECT_SOURCE_DIR}/include/obscura" DESTINATION "${CMAKE_INSTALL_INCLUDEDIR}"
        FILES_MATCHING PATTERN "*.hpp")
install(FILES "${PROJECT_BINARY_DIR}/include/obscura/version.hpp" DESTINATION "${CMAKE_INSTALL_INCLUDEDIR}/obscura")

install(TARGETS obscura EXPORT obscuraTargets
        ARCHIVE DESTINATION "${CMAKE_INSTALL_LIBDIR}"
        LIBRARY DESTINATION "${CMAKE_INSTALL_LIBDIR}"
        RUNTIME DESTINATION "${CMAKE_INSTALL_BINDIR}")
install(EXPORT obscuraTargets NAMESPACE obscura:: DESTINATION "${OBSCURA_CMAKE_DIR}")

set(OBSCURA_COMPONENTS)
foreach(component headless assets reference)
  if(TARGET obscura_${component})
    string(SUBSTRING "${component}" 0 1 first)
    string(TOUPPER "${first}" first)
    string(SUBSTRING "${component}" 1 -1 rest)
    install(TARGETS obscura_${component} EXPORT obscura${first}${rest}Targets
            ARCHIVE DESTINATION "${CMAKE_INSTALL_LIBDIR}"
            LIBRARY DESTINATION "${CMAKE_INSTALL_LIBDIR}"
            RUNTIME DESTINATION "${CMAKE_INSTALL_BINDIR}")
    install(EXPORT obscura${first}${rest}Targets NAMESPACE obscura:: DESTINATION "${OBSCURA_CMAKE_DIR}")
    list(APPEND OBSCURA_COMPONENTS ${component})
  endif()
endforeach()

configure_package_config_file("${PROJECT_SOURCE_DIR}/cmake/obscuraConfig.cmake.in"
  "${PROJECT_BINARY_DIR}/obscuraConfig.cmake" INSTALL_DESTINATION "${OBSCURA_CMAKE_DIR}")
write_basic_package_version_file("${PROJECT_BINARY_DIR}/obscuraConfigVersion.cmake"
  VERSION ${PROJECT_VERSION} COMPATIBILITY SameMinorVersion)
install(FILES "${PROJECT_BINARY_DIR}/obscuraConfig.cmake" "${PROJECT_BINARY_DIR}/obscuraConfigVersion.cmake"
              "${PROJECT_SOURCE_DIR}/cmake/ObscuraDependencies.cmake"
        DESTINATION "${OBSCURA_CMAKE_DIR}")
if(TARGET obscura_cli)
  install(TARGETS obscura_cli RUNTIME DESTINATION "${CMAKE_INSTALL_BINDIR}")
endif()
install(FILES "${PROJECT_SOURCE_DIR}/LICENSE" "${PROJECT_SOURCE_DIR}/README.md" DESTINATION "${CMAKE_INSTALL_DOCDIR}")
