#pragma once
// What the modules reading a G-buffer through shaders/visibility/screen_march.glsl share:
// the checks of the view's textures and their bindings at the VIS_* units.
#include "core/texture_info.hpp"
#include "obscura/gbuffer.hpp"
#include "obscura/screen_visibility.hpp"

#include <string>
#include <vector>

namespace obscura::detail {

struct ContextImpl;

//! Checks that `view` has a depth texture and a normal texture of the same size (and a
//! back layer of that size when `needsBack`), each readable as the passes sample it
//! (requireReadableAs); returns the view with width and height taken from the depth
//! texture. Throws Error{InvalidArgument} naming `owner` or the texture otherwise.
GBufferView checkScreenInputs(ContextImpl& ctx, const GBufferView& view, bool needsBack, const std::string& owner);
//! Throws Error{InvalidArgument} unless GBufferView::<what> `texture` is readable as `kind`
//! (requireReadableAs) and has the size of the checked view (from checkScreenInputs).
void requireViewInput(ContextImpl& ctx, const TextureView& texture, const GBufferView& checked, const std::string& what,
                      SampledAs kind);
//! Binds `texture` at `unit` with the nearest, clamped sampler (what texelFetch readers take).
void bindNearest(ContextImpl& ctx, int unit, GLuint texture);

//! Binds depth, normal (and the back layer for SCREEN_PEELED shaders) with nearest sampling.
void bindScreenInputs(ContextImpl& ctx, const GBufferView& view, bool peeled);
//! The defines that make screen_march.glsl march with `march` and `thickness`.
std::vector<std::string> screenMarchDefines(ScreenMarch march, ScreenThickness thickness);
//! The defines of screen_march.glsl's thickness mode alone (none for Constant).
std::vector<std::string> screenThicknessDefines(ScreenThickness thickness);

} // namespace obscura::detail
