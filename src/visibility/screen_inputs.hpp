#pragma once
// What the modules reading a G-buffer through shaders/visibility/screen_march.glsl share:
// the checks of the view's textures and their bindings at the VIS_* units.
#include "obscura/gbuffer.hpp"

#include <string>

namespace obscura::detail {

struct ContextImpl;

//! Checks that `view` has a depth texture and a normal texture of the same size (and a
//! back layer of that size when `needsBack`); returns the view with width and height taken
//! from the depth texture. Throws Error{InvalidArgument} naming `owner` otherwise.
GBufferView checkScreenInputs(ContextImpl& ctx, const GBufferView& view, bool needsBack, const std::string& owner);
//! Binds depth, normal (and the back layer, when the view has one) with nearest sampling.
void bindScreenInputs(ContextImpl& ctx, const GBufferView& view);

} // namespace obscura::detail
