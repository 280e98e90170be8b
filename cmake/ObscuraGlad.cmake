# Generates our private glad2 GL loader at build time.
#
# --mx gives a per-context function table (GladGLContext) instead of global function pointers,
# so nothing we load can collide with the host's own loader. /usr/bin/glad must be called with
# --reproducible: without it glad downloads the newest Khronos XML, which needs a network.
find_program(OBSCURA_GLAD_EXECUTABLE glad PATHS /usr/bin NO_DEFAULT_PATH)
if(NOT OBSCURA_GLAD_EXECUTABLE)
  find_program(OBSCURA_GLAD_EXECUTABLE glad)
endif()
if(NOT OBSCURA_GLAD_EXECUTABLE)
  message(FATAL_ERROR "glad (glad2) not found: install Debian's python3-glad (scripts/setup-debian.sh)")
endif()

# Extensions we may use where present; everything else is GL 4.5 core.
# Besides KHR_debug, the extensions whose state the state guard saves and resets
# (src/core/state_guard.cpp).
set(OBSCURA_GLAD_EXTENSIONS
    "GL_KHR_debug,GL_NV_conservative_raster,GL_INTEL_conservative_rasterization,GL_EXT_depth_bounds_test,GL_NV_representative_fragment_test,GL_NV_scissor_exclusive,GL_NV_shading_rate_image,GL_INTEL_blackhole_render,GL_NV_clip_space_w_scaling,GL_EXT_window_rectangles,GL_NV_viewport_swizzle")

# obscura_generate_glad(<out_dir> <extra glad c options> ...)
# Generates <out_dir>/include/glad/gl.h and <out_dir>/src/gl.c.
function(obscura_generate_glad out_dir)
  add_custom_command(
    OUTPUT "${out_dir}/src/gl.c" "${out_dir}/include/glad/gl.h" "${out_dir}/include/KHR/khrplatform.h"
    COMMAND "${OBSCURA_GLAD_EXECUTABLE}" --api gl:core=4.5 --extensions "${OBSCURA_GLAD_EXTENSIONS}"
            --out-path "${out_dir}" --reproducible --quiet c ${ARGN}
    COMMENT "Generating glad2 loader in ${out_dir} (${ARGN})"
    VERBATIM)
endfunction()
