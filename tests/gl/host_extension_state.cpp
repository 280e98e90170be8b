#include "host_extension_state.hpp"

#include <glad/gl.h>

#include <utility>

namespace obscura::test {

std::string guardedExtensionsPresent() {
    const std::pair<const char*, int> extensions[] = {
        {"NV_conservative_raster", GLAD_GL_NV_conservative_raster},
        {"INTEL_conservative_rasterization", GLAD_GL_INTEL_conservative_rasterization},
        {"EXT_depth_bounds_test", GLAD_GL_EXT_depth_bounds_test},
        {"NV_representative_fragment_test", GLAD_GL_NV_representative_fragment_test},
        {"NV_scissor_exclusive", GLAD_GL_NV_scissor_exclusive},
        {"NV_shading_rate_image", GLAD_GL_NV_shading_rate_image},
        {"INTEL_blackhole_render", GLAD_GL_INTEL_blackhole_render},
        {"NV_clip_space_w_scaling", GLAD_GL_NV_clip_space_w_scaling},
        {"EXT_window_rectangles", GLAD_GL_EXT_window_rectangles},
        {"NV_viewport_swizzle", GLAD_GL_NV_viewport_swizzle}};
    std::string present;
    for (const auto& [name, flag] : extensions) {
        if (!flag) continue;
        if (!present.empty()) present += ' ';
        present += name;
    }
    return present.empty() ? "none" : present;
}

void setUnusualExtensionState() {
    // Each that can is set so that it would change what our draws write: depth bounds that the G-buffer's cleared depth (1) lies outside, an
    // exclusive scissor over every pixel of viewport 0, a shading rate palette whose entry 0
    // (an unbound shading rate image's) runs no invocations. The representative fragment test
    // acts only on early_fragment_tests shaders, which we do not have: it checks the reset.
    // Blackhole rendering drops every draw and dispatch; W scaling with these coefficients
    // changes the w of every vertex off x = y = 0; two small inclusive window rectangles
    // clip all other pixels; the swizzle mirrors viewport 0. What is set at index 1 checks
    // that only index 0 is touched.
    if (GLAD_GL_INTEL_blackhole_render) glEnable(GL_BLACKHOLE_RENDER_INTEL);
    if (GLAD_GL_NV_clip_space_w_scaling) {
        glViewportPositionWScaleNV(0, 0.5f, -0.25f);
        glViewportPositionWScaleNV(1, 0.125f, 0.75f);
        glEnable(GL_VIEWPORT_POSITION_W_SCALE_NV);
    }
    if (GLAD_GL_EXT_window_rectangles) {
        const GLint boxes[8] = {0, 0, 1, 1, 2, 3, 4, 5};
        glWindowRectanglesEXT(GL_INCLUSIVE_EXT, 2, boxes);
    }
    if (GLAD_GL_NV_viewport_swizzle) {
        glViewportSwizzleNV(0, GL_VIEWPORT_SWIZZLE_NEGATIVE_X_NV, GL_VIEWPORT_SWIZZLE_POSITIVE_Y_NV,
                            GL_VIEWPORT_SWIZZLE_POSITIVE_Z_NV, GL_VIEWPORT_SWIZZLE_POSITIVE_W_NV);
        glViewportSwizzleNV(1, GL_VIEWPORT_SWIZZLE_POSITIVE_Y_NV, GL_VIEWPORT_SWIZZLE_POSITIVE_X_NV,
                            GL_VIEWPORT_SWIZZLE_NEGATIVE_Z_NV, GL_VIEWPORT_SWIZZLE_POSITIVE_W_NV);
    }
    if (GLAD_GL_NV_conservative_raster) glEnable(GL_CONSERVATIVE_RASTERIZATION_NV);
    if (GLAD_GL_INTEL_conservative_rasterization) glEnable(GL_CONSERVATIVE_RASTERIZATION_INTEL);
    if (GLAD_GL_EXT_depth_bounds_test) {
        glEnable(GL_DEPTH_BOUNDS_TEST_EXT);
        glDepthBoundsEXT(0.2, 0.3);
    }
    if (GLAD_GL_NV_representative_fragment_test) glEnable(GL_REPRESENTATIVE_FRAGMENT_TEST_NV);
    if (GLAD_GL_NV_scissor_exclusive) {
        glScissorExclusiveNV(0, 0, 4096, 4096);
        glEnablei(GL_SCISSOR_TEST_EXCLUSIVE_NV, 0);
        glEnablei(GL_SCISSOR_TEST_EXCLUSIVE_NV, 1);
    }
    if (GLAD_GL_NV_shading_rate_image) {
        const GLenum noInvocations = GL_SHADING_RATE_NO_INVOCATIONS_NV;
        glShadingRateImagePaletteNV(0, 0, 1, &noInvocations);
        glEnablei(GL_SHADING_RATE_IMAGE_NV, 0);
        glEnablei(GL_SHADING_RATE_IMAGE_NV, 1);
    }
}

} // namespace obscura::test
