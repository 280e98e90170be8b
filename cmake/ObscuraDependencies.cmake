# Small fixes for Debian 12's packaged CMake configs.

# Debian's OpenImageIO config lists /usr/include/opencv4 in its interface include
# directories even when libopencv-dev is not installed, and CMake refuses non-existent
# include paths of imported targets. Drop the directories that do not exist.
function(obscura_prune_missing_includes target)
  get_target_property(_dirs ${target} INTERFACE_INCLUDE_DIRECTORIES)
  if(NOT _dirs)
    return()
  endif()
  set(_kept)
  foreach(d IN LISTS _dirs)
    if(d MATCHES "^\\$<" OR EXISTS "${d}")
      list(APPEND _kept "${d}")
    endif()
  endforeach()
  set_target_properties(${target} PROPERTIES INTERFACE_INCLUDE_DIRECTORIES "${_kept}")
endfunction()

macro(obscura_find_openimageio)
  find_package(OpenImageIO CONFIG REQUIRED)
  obscura_prune_missing_includes(OpenImageIO::OpenImageIO)
endmacro()
