#include "filters/screen_integrator.hpp"

#include "core/compute.hpp"
#include "core/context_impl.hpp"
#include "core/pass_scope.hpp"
#include "core/texture_info.hpp"
#include "visibility/screen_inputs.hpp"

#include <algorithm>
#include <string>

namespace obscura::detail {
namespace {

std::string label(const IntegratorShape& shape, const char* what) { return std::string(shape.module) + "." + what; }

bool filtered(const IntegratorShape& shape) { return filtersRun(shape.scale, shape.filter.taps); }

void bindWrite(ContextImpl& ctx, int unit, GLuint texture, GLenum format) {
    if (texture) ctx.state.bindImage(ctx, unit, texture, 0, GL_FALSE, 0, GL_WRITE_ONLY, format);
}

} // namespace

glm::ivec2 ScreenIntegrator::reducedSize(const GBufferView& view, int scale) {
    return {(view.width + scale - 1) / scale, (view.height + scale - 1) / scale};
}

std::vector<GLuint> ScreenIntegrator::written(const IntegratorShape& shape) const {
    const bool reduced = shape.scale > 1;
    return {value_.get(), filtered(shape) ? guide_.get() : 0u, shape.direction ? direction_.get() : 0u,
            reduced ? fullValue_.get() : 0u, reduced && shape.direction ? fullDirection_.get() : 0u};
}

void ScreenIntegrator::begin(ContextImpl& ctx, const GBufferView& view, bool peeled, std::uint32_t frameIndex,
                             const IntegratorShape& shape) {
    refinedLastRun_ = false;
    frame_.bind(ctx, view.camera, view.width, view.height, depthStepOf(ctx, view.depth.name), view.normalError, frameIndex);
    bindScreenInputs(ctx, view, peeled);
    ctx.bindNoiseTexture();
    if (shape.hiz) hiz_.build(ctx, view, shape.hizThickness, shape.hizMode, label(shape, "hiz").c_str());
}

IntegratorResult ScreenIntegrator::run(ContextImpl& ctx, const GBufferView& view, const IntegratorShape& shape,
                                       const IntegratorImages& images, const std::function<GLuint(const char*)>& program,
                                       const std::function<void()>& bindInputs) {
    const int scale = shape.scale;
    const glm::ivec2 size = reducedSize(view, scale), fullSize(view.width, view.height);
    const GLenum format = shape.rgb ? GL_RGBA16F : GL_R16F;
    const GLuint value = value_.ensure(ctx, format, size.x, size.y, label(shape, "value"));
    // The guide is only for the filters: a full-resolution result without blur needs none.
    const GLuint guide = filtered(shape) ? guide_.ensure(ctx, GL_RGBA32F, size.x, size.y, label(shape, "guide")) : 0;
    const GLuint direction = shape.direction ? direction_.ensure(ctx, GL_RGBA16F, size.x, size.y, label(shape, "direction")) : 0;
    const bool refine = scale > 1 && shape.filter.refineThreshold > 0.0f;
    GuidedFilterSettings filter = shape.filter;
    filter.geometryTiles = scale > 1 && shape.filter.geometryTiles && GuidedFilters::geometryTilesFit(size);
    const FilterImages filterImages{guide, value, direction, shape.rgb, size, scale, shape.modulate};
    if (filter.geometryTiles) filters_.findGeometryTiles(ctx, filterImages, filter.background, label(shape, "tiles").c_str());
    batches_.plan(ctx, shape.batchItems, shape.iterationsPerItem,
                  std::max(std::size_t(size.x) * std::size_t(size.y),
                           refine ? GuidedFilters::refineCapacity(fullSize) : std::size_t{0}),
                  shape.rayLanes);
    {
        PassScope pass(ctx, shape.pass);
        const GLuint integrator = program(filter.geometryTiles ? "TILES" : nullptr);
        ctx.gl.UseProgram(integrator);
        bindInputs();
        bindWrite(ctx, images.value, value, format);
        bindWrite(ctx, images.guide, guide, GL_RGBA32F);
        bindWrite(ctx, images.direction, direction, GL_RGBA16F);
        batches_.run(ctx, integrator, [&] {
            if (filter.geometryTiles) filters_.dispatchGeometryTiles(ctx);
            else dispatchCompute2D(ctx, size.x, size.y, shape.workgroup);
        });
        ctx.gl.MemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
    }
    filters_.blur(ctx, filterImages, filter, label(shape, "blur").c_str());
    IntegratorResult out{{value, format, size.x, size.y}, {}};
    if (direction) out.direction = {direction, GL_RGBA16F, size.x, size.y};
    if (scale > 1) {
        const GLuint fullValue = fullValue_.ensure(ctx, format, fullSize.x, fullSize.y, label(shape, "output"));
        const GLuint fullDirection =
            direction ? fullDirection_.ensure(ctx, GL_RGBA16F, fullSize.x, fullSize.y, label(shape, "direction_output")) : 0;
        filters_.upsample(ctx, filterImages, filter, fullValue, fullDirection, fullSize, label(shape, "upsample").c_str());
        if (refine) {
            PassScope pass(ctx, label(shape, "refine").c_str());
            const GLuint refinement = program("REFINE");
            ctx.gl.UseProgram(refinement);
            bindWrite(ctx, images.value, fullValue, format);
            bindWrite(ctx, images.direction, fullDirection, GL_RGBA16F);
            batches_.run(ctx, refinement, [&] { filters_.dispatchRefinement(ctx); });
            refinedLastRun_ = true;
        }
        out.value = {fullValue, format, fullSize.x, fullSize.y};
        if (fullDirection) out.direction = {fullDirection, GL_RGBA16F, fullSize.x, fullSize.y};
    }
    if (shape.temporal.enabled)
        temporal_.accumulate(ctx, view, out.value.name, shape.rgb, shape.temporal, label(shape, "temporal").c_str());
    else temporal_.reset(); // not asked for: not kept
    barrierForReaders(ctx);
    return out;
}

void ScreenIntegrator::prepare(ContextImpl& ctx, const IntegratorShape& shape,
                               const std::function<GLuint(const char*)>& program) {
    program(shape.scale > 1 && shape.filter.geometryTiles ? "TILES" : nullptr);
    if (shape.scale > 1 && shape.filter.refineThreshold > 0.0f) program("REFINE");
    if (shape.hiz) HiZPyramid::prepare(ctx, shape.hizMode);
    // Only which images a run gives the filters matters here, not their names.
    GuidedFilterSettings filter = shape.filter;
    filter.geometryTiles = shape.scale > 1 && shape.filter.geometryTiles; // as run() (tiles that fit)
    if (filtered(shape))
        GuidedFilters::prepare(ctx, {1, 1, shape.direction ? 1u : 0u, shape.rgb, {}, shape.scale, shape.modulate ? 1u : 0u},
                               filter);
    if (shape.temporal.enabled) TemporalHistory::prepare(ctx, shape.rgb);
}

RefinementCount ScreenIntegrator::lastRefinement(ContextImpl& ctx) const {
    return refinedLastRun_ ? filters_.refinementCount(ctx) : RefinementCount{};
}

std::size_t ScreenIntegrator::memoryBytes() const {
    return value_.bytes() + direction_.bytes() + guide_.bytes() + fullValue_.bytes() + fullDirection_.bytes() +
           frame_.memoryBytes() + filters_.memoryBytes() + hiz_.memoryBytes() + batches_.memoryBytes() +
           temporal_.memoryBytes();
}

} // namespace obscura::detail
