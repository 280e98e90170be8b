#include "obscura/ambient_occlusion.hpp"

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
#include "shaders/ao/ao_bindings.h"
#include "shaders/voxel/voxel_bindings.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

namespace obscura {
namespace {

using namespace detail;

// The pass names (stable: profiler, debug groups, bench).
const char* passName(AoMethod m) {
    switch (m) {
    case AoMethod::RayMarch: return "ao.raymarch";
    case AoMethod::Points: return "ao.points";
    case AoMethod::Horizon: return "ao.horizon";
    case AoMethod::Voxel: return "ao.voxel";
    }
    return "ao";
}

void validateSettings(const AmbientOcclusionSettings& s) {
    requireEnumerator(s.method, {AoMethod::RayMarch, AoMethod::Points, AoMethod::Horizon, AoMethod::Voxel},
                      "AmbientOcclusionSettings::method");
    requireEnumerator(s.falloff,
                      {ObscuranceFalloff::None, ObscuranceFalloff::Linear, ObscuranceFalloff::Quadratic, ObscuranceFalloff::Smooth},
                      "AmbientOcclusionSettings::falloff");
    requireEnumerator(s.resolution, {AoResolution::Full, AoResolution::Half, AoResolution::Quarter},
                      "AmbientOcclusionSettings::resolution");
    validateScreenModes(s.march, s.thicknessMode, "AmbientOcclusionSettings");
    if (!(s.radius > 0.0f) || !std::isfinite(s.radius))
        throw Error(ErrorCode::InvalidArgument,
                    "AmbientOcclusionSettings::radius must be in (0, inf) world units, got " + std::to_string(s.radius));
    requireInRange(s.rays, s.method == AoMethod::Horizon ? 2 : 1, 1024, "AmbientOcclusionSettings::rays", "");
    if (s.method == AoMethod::Horizon && s.rays % 2 != 0)
        throw Error(ErrorCode::InvalidArgument, "AmbientOcclusionSettings::rays must be even for the horizon method "
                                                "(two directions per slice), got " + std::to_string(s.rays));
    requireInRange(s.steps, 1, 256, "AmbientOcclusionSettings::steps", "");
    if (!(s.thickness >= 0.0f) || std::isinf(s.thickness))
        throw Error(ErrorCode::InvalidArgument, "AmbientOcclusionSettings::thickness must be in [0, inf) world units (0: "
                                                "the radius), got " + std::to_string(s.thickness));
    validateBlurSettings(s.blurRadius, s.blurDepthSigma, s.blurNormalPower, "AmbientOcclusionSettings");
    validateRefineThreshold(s.refineThreshold, "AmbientOcclusionSettings");
    validateRayLanes(s.rayLanes, "AmbientOcclusionSettings::rayLanes");
    if (s.method == AoMethod::Horizon && !s.cosineWeighted)
        throw Error(ErrorCode::InvalidArgument, "the horizon method integrates the cosine-weighted AO only: set "
                                                "AmbientOcclusionSettings::cosineWeighted");
    if (s.method == AoMethod::Horizon && s.falloff != ObscuranceFalloff::None)
        throw Error(ErrorCode::InvalidArgument, "the horizon method finds horizons, not hit distances, so it has no "
                                                "obscurance: set AmbientOcclusionSettings::falloff to None or use "
                                                "another method");
    if (s.method == AoMethod::Voxel) requireVoxelGrid(s.voxels, s.voxelTraversal, "AmbientOcclusionSettings");
    validateTemporalSettings(s.temporal, "AmbientOcclusionSettings");
}

bool filtered(const AmbientOcclusionSettings& s) { return filtersRun(static_cast<int>(s.resolution), s.blurRadius); }

// The pass's rays (horizon: slices) and the loop iterations each may take, for its ray
// batches (core/ray_batches.hpp).
int batchItems(const AmbientOcclusionSettings& s) { return s.method == AoMethod::Horizon ? std::max(s.rays / 2, 1) : s.rays; }

std::int64_t iterationsPerItem(const AmbientOcclusionSettings& s, glm::ivec2 fullSize) {
    switch (s.method) {
    case AoMethod::RayMarch: return screenRayIterations(s.march, s.steps, fullSize);
    case AoMethod::Points: return 8; // the point and radicalInverse3's digits (7 below 3^7 > 1024)
    case AoMethod::Horizon: return 2 * (std::int64_t(s.steps) + 1) + 1;
    case AoMethod::Voxel: return voxelRayIterations(*s.voxels, s.voxelTraversal, s.radius, s.steps) + 1;
    }
    return 1;
}

int falloffCode(ObscuranceFalloff f) {
    switch (f) {
    case ObscuranceFalloff::Linear: return AO_FALLOFF_LINEAR;
    case ObscuranceFalloff::Quadratic: return AO_FALLOFF_QUADRATIC;
    case ObscuranceFalloff::Smooth: return AO_FALLOFF_SMOOTH;
    case ObscuranceFalloff::None: break;
    }
    return AO_FALLOFF_NONE;
}


bool marches(const AmbientOcclusionSettings& s) { return s.method == AoMethod::RayMarch || s.method == AoMethod::Points; }
ScreenThickness thicknessOf(const AmbientOcclusionSettings& s) {
    return marches(s) ? s.thicknessMode : ScreenThickness::Constant;
}
ScreenMarch marchOf(const AmbientOcclusionSettings& s) {
    return s.method == AoMethod::RayMarch ? s.march : ScreenMarch::View;
}

// The integrator's program for the settings; `variant`: "TILES" (over the geometry tiles),
// "REFINE" (the listed pixels at full resolution) or nothing.
GLuint integratorProgram(ContextImpl& ctx, const AmbientOcclusionSettings& s, const char* variant) {
    std::vector<std::string> defines = {"METHOD=" + std::to_string(static_cast<int>(s.method))};
    if (marches(s)) {
        const auto screen = screenMarchDefines(marchOf(s), thicknessOf(s));
        defines.insert(defines.end(), screen.begin(), screen.end());
    }
    if (s.method == AoMethod::Voxel) defines.push_back("TRAVERSAL=" + std::to_string(voxelTraversalCode(s.voxelTraversal)));
    addRayLaneDefine(defines, s.rayLanes);
    if (variant) defines.push_back(variant);
    return ctx.shaders->program({"ao/ao.comp.glsl"}, defines);
}

GuidedFilterSettings filterSettings(const AmbientOcclusionSettings& s, bool tiled) {
    return {s.blurRadius, s.blurDepthSigma, s.blurNormalPower, true, 1.0f, s.refineThreshold, tiled};
}

} // namespace

struct AmbientOcclusion::Impl {
    explicit Impl(ContextImpl& c) : ctx(c) {}

    ContextImpl& ctx;
    FrameUniforms frame;
    HiZPyramid hiz;
    Buffer params;
    SizedTexture ao, bent, guide, fullAo, fullBent;
    GuidedFilters filters;
    RayBatches batches;
    TemporalHistory temporal;
    bool refinedLastRun = false; //!< lastRefinement reads the list

    shader::AoParams makeParams(const GBufferView& g, const AmbientOcclusionSettings& s, glm::ivec2 size, int scale) const {
        shader::AoParams p{};
        p.shape = glm::vec4(s.radius, s.thickness > 0.0f ? s.thickness : s.radius, 0.0f, 0.0f);
        p.counts = glm::ivec4(s.rays, s.steps,
                              (s.cosineWeighted ? AO_FLAG_COSINE : 0) | (s.bentNormals ? AO_FLAG_BENT : 0) |
                                  (filtered(s) ? AO_FLAG_GUIDE : 0),
                              falloffCode(s.falloff));
        p.sizes = glm::ivec4(size, scale, 0);
        p.viewToVoxel = glm::mat4(1.0f);
        if (s.method == AoMethod::Voxel) {
            p.viewToVoxel = viewToVoxel(*s.voxels, g.camera);
            p.shape.z = static_cast<float>(voxelDiagonal(*s.voxels));
            p.voxel = glm::ivec4(voxelTraversalCode(s.voxelTraversal), 0, 0, 0);
        }
        return p;
    }

    void bindWrite(int unit, GLuint texture, GLenum format) {
        ctx.state.bindImage(ctx, unit, texture, 0, GL_FALSE, 0, GL_WRITE_ONLY, format);
    }
};

AmbientOcclusion::AmbientOcclusion(Context& context) : impl_(std::make_unique<Impl>(context.impl())) {}
AmbientOcclusion::~AmbientOcclusion() = default;

AmbientOcclusionView AmbientOcclusion::run(const GBufferView& g, const AmbientOcclusionSettings& s) {
    validateSettings(s);
    auto& d = *impl_;
    auto& ctx = d.ctx;
    analyzeProjection(g.camera);
    const ScreenThickness thickness = thicknessOf(s);
    const bool peeled = depthLayersFor(thickness) == 2;
    const GBufferView view = checkScreenInputs(ctx, g, peeled, "AmbientOcclusionSettings");
    const int scale = static_cast<int>(s.resolution);
    // What this run writes (or reallocates): an earlier run's other outputs may be read.
    const bool reduced = scale > 1;
    requireNotOwnOutput({{"GBufferView::depth", view.depth.name},
                         {"GBufferView::normal", view.normal.name},
                         {"GBufferView::backDepth", peeled ? view.backDepth.name : 0u}},
                        {d.ao.get(), filtered(s) ? d.guide.get() : 0u, s.bentNormals ? d.bent.get() : 0u,
                         reduced ? d.fullAo.get() : 0u, reduced && s.bentNormals ? d.fullBent.get() : 0u},
                        "AmbientOcclusion");
    const glm::ivec2 size((view.width + scale - 1) / scale, (view.height + scale - 1) / scale);

    d.refinedLastRun = false;
    StateScope scope(ctx);
    const shader::AoParams p = d.makeParams(view, s, size, scale);
    if (!d.params) d.params = createBuffer(ctx, sizeof p, nullptr, GL_DYNAMIC_STORAGE_BIT, "ao.params");
    ctx.gl.NamedBufferSubData(d.params.get(), 0, sizeof p, &p);
    ctx.state.bindUniformBuffer(ctx, AO_PARAMS_UBO_BINDING, d.params.get());
    d.frame.bind(ctx, view.camera, view.width, view.height, depthStepOf(ctx, view.depth.name), view.normalError,
                 s.frameIndex);
    bindScreenInputs(ctx, view, peeled);
    ctx.bindNoiseTexture();
    if (marchOf(s) == ScreenMarch::HiZ) d.hiz.build(ctx, view, p.shape.y, thickness, "ao.hiz");
    const GLuint aoTexture = d.ao.ensure(ctx, GL_R16F, size.x, size.y, "ao.occlusion");
    // The guide is only for the filters: a full-resolution result without blur needs none.
    const GLuint guide = filtered(s) ? d.guide.ensure(ctx, GL_RGBA32F, size.x, size.y, "ao.guide") : 0;
    const GLuint bent = s.bentNormals ? d.bent.ensure(ctx, GL_RGBA16F, size.x, size.y, "ao.bent") : 0;
    const bool refine = scale > 1 && s.refineThreshold > 0.0f;
    const bool tiled = scale > 1 && s.geometryTiles && GuidedFilters::geometryTilesFit(size);
    const FilterImages images{guide, aoTexture, bent, false, size, scale};
    const GuidedFilterSettings filter = filterSettings(s, tiled);
    if (tiled) d.filters.findGeometryTiles(ctx, images, filter.background, "ao.tiles");
    d.batches.plan(ctx, batchItems(s), iterationsPerItem(s, {view.width, view.height}),
                   std::max(std::size_t(size.x) * std::size_t(size.y),
                            refine ? GuidedFilters::refineCapacity({view.width, view.height}) : std::size_t{0}),
                   s.rayLanes);
    {
        PassScope pass(ctx, passName(s.method));
        const GLuint program = integratorProgram(ctx, s, tiled ? "TILES" : nullptr);
        ctx.gl.UseProgram(program);
        if (s.method == AoMethod::Voxel) bindVoxelGrid(ctx, *s.voxels);
        d.bindWrite(AO_OUT_IMAGE, aoTexture, GL_R16F);
        if (guide) d.bindWrite(AO_GUIDE_OUT_IMAGE, guide, GL_RGBA32F);
        if (bent) d.bindWrite(AO_BENT_OUT_IMAGE, bent, GL_RGBA16F);
        d.batches.run(ctx, program, [&] {
            if (tiled) d.filters.dispatchGeometryTiles(ctx);
            else dispatchCompute2D(ctx, size.x, size.y, AO_WORKGROUP);
        });
        ctx.gl.MemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
    }
    d.filters.blur(ctx, images, filter, "ao.blur");
    AmbientOcclusionView out;
    out.width = view.width;
    out.height = view.height;
    if (scale == 1) {
        out.ao = {aoTexture, GL_R16F, size.x, size.y};
        if (bent) out.bentNormal = {bent, GL_RGBA16F, size.x, size.y};
    } else {
        const GLuint fullAo = d.fullAo.ensure(ctx, GL_R16F, view.width, view.height, "ao.output");
        const GLuint fullBent = bent ? d.fullBent.ensure(ctx, GL_RGBA16F, view.width, view.height, "ao.bent_normal") : 0;
        d.filters.upsample(ctx, images, filter, fullAo, fullBent, {view.width, view.height}, "ao.upsample");
        if (refine) {
            PassScope pass(ctx, "ao.refine");
            const GLuint program = integratorProgram(ctx, s, "REFINE");
            ctx.gl.UseProgram(program);
            d.bindWrite(AO_OUT_IMAGE, fullAo, GL_R16F);
            if (bent) d.bindWrite(AO_BENT_OUT_IMAGE, fullBent, GL_RGBA16F);
            d.batches.run(ctx, program, [&] { d.filters.dispatchRefinement(ctx); });
            d.refinedLastRun = true;
        }
        out.ao = {fullAo, GL_R16F, view.width, view.height};
        if (bent) out.bentNormal = {fullBent, GL_RGBA16F, view.width, view.height};
    }
    if (s.temporal.enabled) d.temporal.accumulate(ctx, view, out.ao.name, false, s.temporal, "ao.temporal");
    else d.temporal.reset(); // not asked for: not kept
    barrierForReaders(ctx);
    return out;
}

void AmbientOcclusion::prepare(const AmbientOcclusionSettings& s) {
    validateSettings(s);
    auto& ctx = impl_->ctx;
    StateScope scope(ctx);
    const int scale = static_cast<int>(s.resolution);
    const bool tiled = scale > 1 && s.geometryTiles;
    if (marchOf(s) == ScreenMarch::HiZ) HiZPyramid::prepare(ctx, thicknessOf(s));
    integratorProgram(ctx, s, tiled ? "TILES" : nullptr);
    if (scale > 1 && s.refineThreshold > 0.0f) integratorProgram(ctx, s, "REFINE");
    // Only which images a run gives the filters matters here, not their names.
    if (filtered(s)) GuidedFilters::prepare(ctx, {1, 1, s.bentNormals ? 1u : 0u, false, {}, scale}, filterSettings(s, tiled));
    if (s.temporal.enabled) TemporalHistory::prepare(ctx, false);
}

void AmbientOcclusion::resetHistory() { impl_->temporal.reset(); }

RefinementCount AmbientOcclusion::lastRefinement() const {
    return impl_->refinedLastRun ? impl_->filters.refinementCount(impl_->ctx) : RefinementCount{};
}

std::size_t AmbientOcclusion::memoryBytes() const {
    const auto& d = *impl_;
    return d.ao.bytes() + d.bent.bytes() + d.guide.bytes() + d.fullAo.bytes() + d.fullBent.bytes() + d.frame.memoryBytes() +
           d.filters.memoryBytes() + d.hiz.memoryBytes() + d.batches.memoryBytes() + d.temporal.memoryBytes() +
           (d.params ? sizeof(shader::AoParams) : 0);
}

} // namespace obscura
