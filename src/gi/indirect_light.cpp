#include "obscura/indirect_light.hpp"

#include "core/compute.hpp"
#include "core/context_impl.hpp"
#include "core/frame_uniforms.hpp"
#include "core/pass_scope.hpp"
#include "core/ray_batches.hpp"
#include "core/shader_library.hpp"
#include "core/texture_info.hpp"
#include "core/validate.hpp"
#include "filters/guided_filters.hpp"
#include "filters/temporal_history.hpp"
#include "visibility/hiz_pyramid.hpp"
#include "visibility/screen_inputs.hpp"
#include "voxel/voxel_queries.hpp"
#include "obscura/context.hpp"
#include "shaders/gi/gi_bindings.h"
#include "shaders/voxel/voxel_bindings.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

namespace obscura {
namespace {

using namespace detail;

void validateSettings(const IndirectLightSettings& s) {
    requireEnumerator(s.method, {GiMethod::Screen, GiMethod::Hybrid}, "IndirectLightSettings::method");
    requireEnumerator(s.resolution, {AoResolution::Full, AoResolution::Half, AoResolution::Quarter},
                      "IndirectLightSettings::resolution");
    validateScreenModes(s.march, s.thicknessMode, "IndirectLightSettings");
    if (!(s.radius > 0.0f) || !std::isfinite(s.radius))
        throw Error(ErrorCode::InvalidArgument,
                    "IndirectLightSettings::radius must be in (0, inf) world units, got " + std::to_string(s.radius));
    requireInRange(s.rays, 1, 1024, "IndirectLightSettings::rays", "");
    requireInRange(s.steps, 1, 256, "IndirectLightSettings::steps", "");
    if (!(s.thickness >= 0.0f) || std::isinf(s.thickness))
        throw Error(ErrorCode::InvalidArgument, "IndirectLightSettings::thickness must be in [0, inf) world units, got " +
                                                    std::to_string(s.thickness));
    validateBlurSettings(s.blurRadius, s.blurDepthSigma, s.blurNormalPower, "IndirectLightSettings");
    validateRefineThreshold(s.refineThreshold, "IndirectLightSettings");
    validateRayLanes(s.rayLanes, "IndirectLightSettings::rayLanes");
    if (s.method == GiMethod::Hybrid) requireVoxelGrid(s.voxels, s.voxelTraversal, "IndirectLightSettings");
    validateTemporalSettings(s.temporal, "IndirectLightSettings");
}

bool filtered(const IndirectLightSettings& s) { return filtersRun(static_cast<int>(s.resolution), s.blurRadius); }

bool hybrid(const IndirectLightSettings& s) { return s.method == GiMethod::Hybrid; }
ScreenThickness thicknessOf(const IndirectLightSettings& s) {
    return hybrid(s) ? ScreenThickness::Constant : s.thicknessMode;
}

// The integrator's program for the settings; `variant`: "TILES", "REFINE" or nothing (as AO's).
GLuint integratorProgram(ContextImpl& ctx, const IndirectLightSettings& s, const char* variant) {
    std::vector<std::string> defines = {"METHOD=" + std::to_string(hybrid(s) ? GI_METHOD_HYBRID : GI_METHOD_SCREEN)};
    if (hybrid(s)) defines.push_back("TRAVERSAL=" + std::to_string(voxelTraversalCode(s.voxelTraversal)));
    else {
        const auto screen = screenMarchDefines(s.march, thicknessOf(s));
        defines.insert(defines.end(), screen.begin(), screen.end());
    }
    addRayLaneDefine(defines, s.rayLanes);
    if (variant) defines.push_back(variant);
    return ctx.shaders->program({"gi/gi.comp.glsl"}, defines);
}

GuidedFilterSettings filterSettings(const IndirectLightSettings& s, bool tiled) {
    return {s.blurRadius, s.blurDepthSigma, s.blurNormalPower, false, 0.0f, s.refineThreshold, tiled};
}

} // namespace

struct IndirectLight::Impl {
    explicit Impl(ContextImpl& c) : ctx(c) {}

    ContextImpl& ctx;
    FrameUniforms frame;
    HiZPyramid hiz;
    Buffer params;
    SizedTexture radiance, guide, full;
    GuidedFilters filters;
    RayBatches batches;
    TemporalHistory temporal;
    bool refinedLastRun = false; //!< lastRefinement reads the list

    void bindRead(int unit, GLuint texture) {
        ctx.state.bindTexture(ctx, unit, texture);
        ctx.state.bindSampler(ctx, unit, ctx.nearestClampSampler());
    }

    void bindWrite(int unit, GLuint texture, GLenum format) {
        ctx.state.bindImage(ctx, unit, texture, 0, GL_FALSE, 0, GL_WRITE_ONLY, format);
    }

    float thickness = 0.0f; // of the last run, world units (params.shape.y)

    void uploadParams(const GBufferView& g, const IndirectLightSettings& s, glm::ivec2 size, int scale) {
        shader::GiParams p{};
        p.shape = glm::vec4(s.radius, s.thickness > 0.0f ? s.thickness : s.radius, 0.0f, 0.0f);
        p.counts = glm::ivec4(s.rays, s.steps, filtered(s) ? 1 : 0, 0);
        p.sizes = glm::ivec4(size, scale, 0);
        p.viewToVoxel = glm::mat4(1.0f);
        if (s.method == GiMethod::Hybrid) {
            p.viewToVoxel = viewToVoxel(*s.voxels, g.camera);
            // As voxel AO: rays start about a voxel diagonal off the surface (plus the depth's
            // error and the normal bound, surface_rays.glsl); a voxel hit lies
            // within a voxel diagonal of the surface it stands for, so two diagonals is the
            // default tolerance for finding that surface on screen.
            p.shape.z = static_cast<float>(voxelDiagonal(*s.voxels));
            if (s.thickness <= 0.0f) p.shape.y = 2.0f * p.shape.z;
        }
        thickness = p.shape.y;
        if (!params) params = createBuffer(ctx, sizeof p, nullptr, GL_DYNAMIC_STORAGE_BIT, "gi.params");
        ctx.gl.NamedBufferSubData(params.get(), 0, sizeof p, &p);
        ctx.state.bindUniformBuffer(ctx, GI_PARAMS_UBO_BINDING, params.get());
    }

};

IndirectLight::IndirectLight(Context& context) : impl_(std::make_unique<Impl>(context.impl())) {}
IndirectLight::~IndirectLight() = default;

IndirectLightView IndirectLight::run(const GBufferView& g, const IndirectLightSettings& s) {
    validateSettings(s);
    auto& d = *impl_;
    auto& ctx = d.ctx;
    analyzeProjection(g.camera);
    if (!g.albedo || !g.directRadiance)
        throw Error(ErrorCode::InvalidArgument, "indirect light gathers the G-buffer's direct radiance and albedo: render "
                                                "the G-buffer with GBuffer::render, or give HostGBuffer::albedo and "
                                                "directRadiance to GBuffer::adopt");
    const bool hybrid = s.method == GiMethod::Hybrid;
    const ScreenThickness thickness = thicknessOf(s);
    const bool peeled = depthLayersFor(thickness) == 2;
    const GBufferView view = checkScreenInputs(ctx, g, peeled, "IndirectLightSettings");
    requireViewInput(ctx, g.albedo, view, "albedo", SampledAs::Rgb);
    requireViewInput(ctx, g.directRadiance, view, "directRadiance", SampledAs::Rgb);
    requireNotOwnOutput({{"GBufferView::depth", view.depth.name},
                         {"GBufferView::normal", view.normal.name},
                         {"GBufferView::backDepth", peeled ? view.backDepth.name : 0u},
                         {"GBufferView::albedo", g.albedo.name},
                         {"GBufferView::directRadiance", g.directRadiance.name}},
                        {d.radiance.get(), filtered(s) ? d.guide.get() : 0u,
                         s.resolution != AoResolution::Full ? d.full.get() : 0u},
                        "IndirectLight"); // what this run writes: an earlier run's other output may be read
    const int scale = static_cast<int>(s.resolution);
    const glm::ivec2 fullSize(view.width, view.height);
    const glm::ivec2 size((fullSize.x + scale - 1) / scale, (fullSize.y + scale - 1) / scale);

    d.refinedLastRun = false;
    StateScope scope(ctx);
    d.uploadParams(g, s, size, scale);
    d.frame.bind(ctx, g.camera, fullSize.x, fullSize.y, depthStepOf(ctx, view.depth.name), view.normalError, s.frameIndex);
    bindScreenInputs(ctx, view, peeled);
    if (!hybrid && s.march == ScreenMarch::HiZ) d.hiz.build(ctx, view, d.thickness, thickness, "gi.hiz");
    d.bindRead(GI_RADIANCE_UNIT, g.directRadiance.name);
    d.bindRead(GI_ALBEDO_UNIT, g.albedo.name);
    ctx.bindNoiseTexture();
    const GLuint radiance = d.radiance.ensure(ctx, GL_RGBA16F, size.x, size.y, "gi.radiance");
    // The guide is only for the filters: a full-resolution result without blur needs none.
    const GLuint guide = filtered(s) ? d.guide.ensure(ctx, GL_RGBA32F, size.x, size.y, "gi.guide") : 0;
    const bool refine = scale > 1 && s.refineThreshold > 0.0f;
    const bool tiled = scale > 1 && s.geometryTiles && GuidedFilters::geometryTilesFit(size);
    const FilterImages images{guide, radiance, 0, true, size, scale, g.albedo.name};
    const GuidedFilterSettings filter = filterSettings(s, tiled);
    if (tiled) d.filters.findGeometryTiles(ctx, images, filter.background, "gi.tiles");
    const std::int64_t perRay = hybrid ? voxelRayIterations(*s.voxels, s.voxelTraversal, s.radius, s.steps) + 1
                                       : screenRayIterations(s.march, s.steps, fullSize);
    d.batches.plan(ctx, s.rays, perRay,
                   std::max(std::size_t(size.x) * std::size_t(size.y), refine ? GuidedFilters::refineCapacity(fullSize) : std::size_t{0}),
                   s.rayLanes);
    {
        PassScope pass(ctx, hybrid ? "gi.hybrid" : "gi.screen");
        const GLuint program = integratorProgram(ctx, s, tiled ? "TILES" : nullptr);
        ctx.gl.UseProgram(program);
        if (hybrid) bindVoxelGrid(ctx, *s.voxels);
        d.bindWrite(GI_OUT_IMAGE, radiance, GL_RGBA16F);
        if (guide) d.bindWrite(GI_GUIDE_OUT_IMAGE, guide, GL_RGBA32F);
        d.batches.run(ctx, program, [&] {
            if (tiled) d.filters.dispatchGeometryTiles(ctx);
            else dispatchCompute2D(ctx, size.x, size.y, GI_WORKGROUP);
        });
        ctx.gl.MemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
    }
    d.filters.blur(ctx, images, filter, "gi.blur");
    IndirectLightView out{{radiance, GL_RGBA16F, size.x, size.y}, fullSize.x, fullSize.y};
    if (scale > 1) {
        const GLuint full = d.full.ensure(ctx, GL_RGBA16F, fullSize.x, fullSize.y, "gi.output");
        d.filters.upsample(ctx, images, filter, full, 0, fullSize, "gi.upsample");
        if (refine) {
            PassScope pass(ctx, "gi.refine");
            const GLuint program = integratorProgram(ctx, s, "REFINE");
            ctx.gl.UseProgram(program);
            d.bindWrite(GI_OUT_IMAGE, full, GL_RGBA16F);
            d.batches.run(ctx, program, [&] { d.filters.dispatchRefinement(ctx); });
            d.refinedLastRun = true;
        }
        out.radiance = {full, GL_RGBA16F, fullSize.x, fullSize.y};
    }
    if (s.temporal.enabled) d.temporal.accumulate(ctx, view, out.radiance.name, true, s.temporal, "gi.temporal");
    else d.temporal.reset(); // not asked for: not kept
    barrierForReaders(ctx);
    return out;
}

void IndirectLight::prepare(const IndirectLightSettings& s) {
    validateSettings(s);
    auto& ctx = impl_->ctx;
    StateScope scope(ctx);
    const int scale = static_cast<int>(s.resolution);
    const bool tiled = scale > 1 && s.geometryTiles;
    if (!hybrid(s) && s.march == ScreenMarch::HiZ) HiZPyramid::prepare(ctx, thicknessOf(s));
    integratorProgram(ctx, s, tiled ? "TILES" : nullptr);
    if (scale > 1 && s.refineThreshold > 0.0f) integratorProgram(ctx, s, "REFINE");
    // Only which images a run gives the filters matters here: the radiance (rgb) and the albedo.
    if (filtered(s)) GuidedFilters::prepare(ctx, {1, 1, 0, true, {}, scale, 1}, filterSettings(s, tiled));
    if (s.temporal.enabled) TemporalHistory::prepare(ctx, true);
}

void IndirectLight::resetHistory() { impl_->temporal.reset(); }

RefinementCount IndirectLight::lastRefinement() const {
    return impl_->refinedLastRun ? impl_->filters.refinementCount(impl_->ctx) : RefinementCount{};
}

std::size_t IndirectLight::memoryBytes() const {
    const auto& d = *impl_;
    return d.radiance.bytes() + d.guide.bytes() + d.full.bytes() + d.frame.memoryBytes() + d.filters.memoryBytes() +
           d.hiz.memoryBytes() + d.batches.memoryBytes() + d.temporal.memoryBytes() + (d.params ? sizeof(shader::GiParams) : 0);
}

} // namespace obscura
