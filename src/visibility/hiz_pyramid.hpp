#pragma once
// The min/max view-z pyramid that screenMarchHiZ (shaders/visibility/screen_march.glsl)
// skips samples with: built per G-buffer view and thickness, bound at VIS_HIZ_UNIT. Shared
// by ScreenVisibility and the integrators that march with ScreenMarch::HiZ.
#include "core/gl_objects.hpp"
#include "obscura/gbuffer.hpp"
#include "obscura/screen_visibility.hpp"

#include <cstddef>

namespace obscura::detail {

struct ContextImpl;

class HiZPyramid {
public:
    //! Builds the pyramid of `view` (checked by checkScreenInputs, inputs bound by
    //! bindScreenInputs) in pass "<pass>": `thickness` world units behind each depth pixel
    //! or down to its back layer, as `mode` says. Leaves it bound at VIS_HIZ_UNIT.
    void build(ContextImpl& ctx, const GBufferView& view, float thickness, ScreenThickness mode, const char* pass);
    std::size_t memoryBytes() const;
    //! Compiles the programs build() uses for `mode`, ahead of time.
    static void prepare(ContextImpl& ctx, ScreenThickness mode);

private:
    static GLuint levelZeroProgram(ContextImpl& ctx, ScreenThickness mode);
    static GLuint reduceProgram(ContextImpl& ctx);

    Texture texture_;
    glm::ivec2 size_{0};
    int levels_ = 0;
};

} // namespace obscura::detail
