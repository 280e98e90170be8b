#include "core/extension_state.hpp"

#include <iterator>

namespace obscura::detail {
namespace {

// Each of these enables can change which pixels our draws write: conservative rasterization
// adds fragments; the depth bounds test (against the depth already stored: our G-buffer's
// clear value) and the exclusive scissor drop some; a shading rate image shades several
// pixels with one invocation, or none. The representative fragment test drops fragments only
// of shaders with early_fragment_tests (none of ours today); it is reset so that one added
// later cannot lose pixels. The exclusive scissor and the shading rate image are per viewport:
// only index 0, the one we draw with, is touched. Blackhole rendering turns every draw,
// dispatch and blit into a no-op, and viewport W scaling divides our clip positions by another
// w; its coefficients are left alone, as they act only when enabled.
struct ExtensionEnable {
    int GladGLContext::*present;
    GLenum cap;
    bool indexed;
};
constexpr ExtensionEnable kEnables[] = {
    {&GladGLContext::NV_conservative_raster, GL_CONSERVATIVE_RASTERIZATION_NV, false},
    {&GladGLContext::INTEL_conservative_rasterization, GL_CONSERVATIVE_RASTERIZATION_INTEL, false},
    {&GladGLContext::EXT_depth_bounds_test, GL_DEPTH_BOUNDS_TEST_EXT, false},
    {&GladGLContext::NV_representative_fragment_test, GL_REPRESENTATIVE_FRAGMENT_TEST_NV, false},
    {&GladGLContext::NV_scissor_exclusive, GL_SCISSOR_TEST_EXCLUSIVE_NV, true},
    {&GladGLContext::NV_shading_rate_image, GL_SHADING_RATE_IMAGE_NV, true},
    {&GladGLContext::INTEL_blackhole_render, GL_BLACKHOLE_RENDER_INTEL, false},
    {&GladGLContext::NV_clip_space_w_scaling, GL_VIEWPORT_POSITION_W_SCALE_NV, false}};
static_assert(std::size(kEnables) == ExtensionState::kEnableCount, "ExtensionState::enables holds one per table row");

bool isEnabled(GladGLContext& gl, const ExtensionEnable& e) { return e.indexed ? gl.IsEnabledi(e.cap, 0) : gl.IsEnabled(e.cap); }

void setEnabled(GladGLContext& gl, const ExtensionEnable& e, bool on) {
    if (e.indexed) on ? gl.Enablei(e.cap, 0) : gl.Disablei(e.cap, 0);
    else on ? gl.Enable(e.cap) : gl.Disable(e.cap);
}

// Window rectangles (EXT_window_rectangles) clip every draw, clear and blit into any
// framebuffer: inclusive ones to their union, exclusive ones to the rest.
void applyWindowRectangles(GladGLContext& gl, GLint mode, const std::vector<GLint>& boxes) {
    gl.WindowRectanglesEXT(static_cast<GLenum>(mode), static_cast<GLsizei>(boxes.size() / 4),
                           boxes.empty() ? nullptr : boxes.data());
}

// A viewport swizzle (NV_viewport_swizzle) permutes and negates the clip coordinates of
// everything drawn through that viewport: ours is index 0, identity in GL's initial state.
constexpr GLenum kViewportSwizzleQueries[4] = {GL_VIEWPORT_SWIZZLE_X_NV, GL_VIEWPORT_SWIZZLE_Y_NV,
                                               GL_VIEWPORT_SWIZZLE_Z_NV, GL_VIEWPORT_SWIZZLE_W_NV};
constexpr GLint kIdentitySwizzle[4] = {GL_VIEWPORT_SWIZZLE_POSITIVE_X_NV, GL_VIEWPORT_SWIZZLE_POSITIVE_Y_NV,
                                       GL_VIEWPORT_SWIZZLE_POSITIVE_Z_NV, GL_VIEWPORT_SWIZZLE_POSITIVE_W_NV};

void applyViewportSwizzle(GladGLContext& gl, const GLint (&swizzle)[4]) {
    gl.ViewportSwizzleNV(0, static_cast<GLenum>(swizzle[0]), static_cast<GLenum>(swizzle[1]),
                         static_cast<GLenum>(swizzle[2]), static_cast<GLenum>(swizzle[3]));
}

} // namespace

void ExtensionState::save(GladGLContext& gl) {
    for (std::size_t i = 0; i < std::size(kEnables); ++i)
        if (gl.*kEnables[i].present) enables[i] = isEnabled(gl, kEnables[i]);
    if (gl.EXT_window_rectangles) {
        GLint count = 0;
        gl.GetIntegerv(GL_WINDOW_RECTANGLE_MODE_EXT, &windowRectangleMode);
        gl.GetIntegerv(GL_NUM_WINDOW_RECTANGLES_EXT, &count);
        windowRectangles.resize(4 * static_cast<std::size_t>(count));
        for (std::size_t i = 0; i < windowRectangles.size() / 4; ++i)
            gl.GetIntegeri_v(GL_WINDOW_RECTANGLE_EXT, static_cast<GLuint>(i), &windowRectangles[4 * i]);
    }
    if (gl.NV_viewport_swizzle)
        for (int i = 0; i < 4; ++i) gl.GetIntegeri_v(kViewportSwizzleQueries[i], 0, &viewportSwizzle[i]);
}

void ExtensionState::restore(GladGLContext& gl) const {
    for (std::size_t i = 0; i < std::size(kEnables); ++i)
        if (gl.*kEnables[i].present) setEnabled(gl, kEnables[i], enables[i]);
    if (gl.EXT_window_rectangles) applyWindowRectangles(gl, windowRectangleMode, windowRectangles);
    if (gl.NV_viewport_swizzle) applyViewportSwizzle(gl, viewportSwizzle);
}

void ExtensionState::applyBaseline(GladGLContext& gl) {
    for (const ExtensionEnable& e : kEnables)
        if (gl.*e.present) setEnabled(gl, e, false);
    if (gl.EXT_window_rectangles) applyWindowRectangles(gl, GL_EXCLUSIVE_EXT, {});
    if (gl.NV_viewport_swizzle) applyViewportSwizzle(gl, kIdentitySwizzle);
}

} // namespace obscura::detail
