#include "visibility/hiz_pyramid.hpp"

#include "core/compute.hpp"
#include "core/context_impl.hpp"
#include "core/pass_scope.hpp"
#include "core/shader_library.hpp"
#include "shaders/visibility/visibility_bindings.h"
#include "visibility/screen_inputs.hpp"

#include <algorithm>
#include <bit>

namespace obscura::detail {

GLuint HiZPyramid::levelZeroProgram(ContextImpl& ctx, ScreenThickness mode) {
    Defines level0{"LEVEL0"};
    for (std::string& d : screenThicknessDefines(mode)) level0.push_back(std::move(d));
    return ctx.shaders->program({"visibility/hiz_build.comp.glsl"}, level0);
}

GLuint HiZPyramid::reduceProgram(ContextImpl& ctx) { return ctx.shaders->program({"visibility/hiz_build.comp.glsl"}, {"REDUCE"}); }

void HiZPyramid::prepare(ContextImpl& ctx, ScreenThickness mode) {
    levelZeroProgram(ctx, mode);
    reduceProgram(ctx);
}

// The pyramid is padded to powers of two, so that level L's cell i covers the pixels
// [i 2^L, (i + 1) 2^L) with GL's halving mip sizes.
void HiZPyramid::build(ContextImpl& ctx, const GBufferView& view, float thickness, ScreenThickness mode, const char* pass) {
    const glm::ivec2 size(std::bit_ceil(static_cast<unsigned>(view.width)), std::bit_ceil(static_cast<unsigned>(view.height)));
    const int levels = std::bit_width(static_cast<unsigned>(std::max(size.x, size.y)));
    if (!texture_ || size != size_) {
        texture_ = createTexture2D(ctx, GL_RG32F, size.x, size.y, levels, "visibility.hiz");
        size_ = size;
        levels_ = levels;
    }
    PassScope scope(ctx, pass);
    auto& gl = ctx.gl;
    GLuint program = levelZeroProgram(ctx, mode);
    gl.UseProgram(program);
    gl.ProgramUniform1f(program, VIS_LOC_THICKNESS, thickness);
    ctx.state.bindImage(ctx, VIS_HIZ_WRITE_IMAGE, texture_.get(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RG32F);
    dispatchCompute2D(ctx, size.x, size.y, VIS_WORKGROUP_2D);
    program = reduceProgram(ctx);
    gl.UseProgram(program);
    for (int level = 1; level < levels; ++level) {
        gl.MemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
        ctx.state.bindImage(ctx, VIS_HIZ_READ_IMAGE, texture_.get(), level - 1, GL_FALSE, 0, GL_READ_ONLY, GL_RG32F);
        ctx.state.bindImage(ctx, VIS_HIZ_WRITE_IMAGE, texture_.get(), level, GL_FALSE, 0, GL_WRITE_ONLY, GL_RG32F);
        dispatchCompute2D(ctx, std::max(1, size.x >> level), std::max(1, size.y >> level), VIS_WORKGROUP_2D);
    }
    gl.MemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT);
    ctx.state.bindTexture(ctx, VIS_HIZ_UNIT, texture_.get());
    ctx.state.bindSampler(ctx, VIS_HIZ_UNIT, ctx.nearestClampSampler());
}

std::size_t HiZPyramid::memoryBytes() const {
    std::size_t bytes = 0;
    for (int level = 0; texture_ && level < levels_; ++level)
        bytes += 8u * std::size_t(std::max(1, size_.x >> level)) * std::size_t(std::max(1, size_.y >> level));
    return bytes;
}

} // namespace obscura::detail
