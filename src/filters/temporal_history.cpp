#include "filters/temporal_history.hpp"

#include "core/compute.hpp"
#include "core/context_impl.hpp"
#include "core/pass_scope.hpp"
#include "core/shader_library.hpp"
#include "core/validate.hpp"
#include "shaders/filters/filter_bindings.h"

namespace obscura::detail {
namespace {

GLuint temporalProgram(ContextImpl& ctx, bool rgb) {
    return ctx.shaders->program({"filters/temporal.comp.glsl"}, rgb ? Defines{"RGB"} : Defines{});
}

} // namespace

void TemporalHistory::accumulate(ContextImpl& ctx, const GBufferView& view, GLuint value, bool rgb,
                                 const TemporalSettings& s, const char* passName) {
    PassScope pass(ctx, passName);
    const glm::ivec2 size(view.width, view.height);
    if (size != size_ || rgb != rgb_) latest_ = -1; // nothing to reproject from
    size_ = size;
    rgb_ = rgb;
    const int next = latest_ == 0 ? 1 : 0;
    const GLuint historyOut = history_[next].ensure(ctx, GL_RGBA16F, size.x, size.y, "filters.temporal_history");
    const GLuint geometryOut = geometry_[next].ensure(ctx, GL_RG32UI, size.x, size.y, "filters.temporal_geometry");
    shader::TemporalParams p{};
    p.previousView = glm::mat4(previousView_);
    p.previousViewProjection = glm::mat4(previousProjection_ * previousView_); // composed in double
    p.depthTolerance = s.depthTolerance;
    p.normalThreshold = s.normalThreshold;
    p.maxFrames = float(s.maxFrames);
    p.previousRayScale = previousRays_.xyScale;
    p.previousRayOffset = previousRays_.xyOffset;
    p.hasHistory = latest_ >= 0 ? 1 : 0;
    p.previousPerspective = previousRays_.kind == ProjectionKind::Perspective ? 1 : 0;
    uploadUniformBlock(ctx, params_, p, TEMPORAL_PARAMS_UBO_BINDING, "filters.temporal_params");
    // Without a history the shader reads none: the other pair (allocated, undefined) only
    // gives the read units valid images.
    const int read = latest_ >= 0 ? latest_ : 1 - next;
    const GLuint historyIn = history_[read].ensure(ctx, GL_RGBA16F, size.x, size.y, "filters.temporal_history");
    const GLuint geometryIn = geometry_[read].ensure(ctx, GL_RG32UI, size.x, size.y, "filters.temporal_geometry");
    ctx.state.bindImage(ctx, TEMPORAL_HISTORY_IMAGE, historyIn, 0, GL_FALSE, 0, GL_READ_ONLY, GL_RGBA16F);
    ctx.state.bindImage(ctx, TEMPORAL_GEOMETRY_IMAGE, geometryIn, 0, GL_FALSE, 0, GL_READ_ONLY, GL_RG32UI);
    ctx.state.bindImage(ctx, TEMPORAL_VALUE_IMAGE, value, 0, GL_FALSE, 0, GL_READ_WRITE, rgb ? GL_RGBA16F : GL_R16F);
    ctx.state.bindImage(ctx, TEMPORAL_HISTORY_OUT_IMAGE, historyOut, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA16F);
    ctx.state.bindImage(ctx, TEMPORAL_GEOMETRY_OUT_IMAGE, geometryOut, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RG32UI);
    ctx.gl.UseProgram(temporalProgram(ctx, rgb));
    dispatchCompute2D(ctx, size.x, size.y, FILTER_WORKGROUP);
    ctx.gl.MemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
    latest_ = next;
    previousView_ = glm::dmat4(view.camera.view);
    previousProjection_ = glm::dmat4(view.camera.projection);
    previousRays_ = depthReconstruction(view.camera);
}

void TemporalHistory::reset() noexcept {
    for (int i = 0; i < 2; ++i) {
        history_[i].release();
        geometry_[i].release();
    }
    latest_ = -1;
}

std::size_t TemporalHistory::memoryBytes() const {
    return history_[0].bytes() + history_[1].bytes() + geometry_[0].bytes() + geometry_[1].bytes() +
           (params_ ? sizeof(shader::TemporalParams) : 0);
}

void TemporalHistory::prepare(ContextImpl& ctx, bool rgb) { temporalProgram(ctx, rgb); }

} // namespace obscura::detail
