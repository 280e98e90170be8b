#include "obscura/ambient_occlusion.hpp"

#include "core/compute.hpp"
#include "core/context_impl.hpp"
#include "core/frame_uniforms.hpp"
#include "core/pass_scope.hpp"
#include "core/ray_batches.hpp"
#include "core/shader_library.hpp"
#include "core/texture_info.hpp"
#include "core/validate.hpp"
#include "filters/screen_integrator.hpp"
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

// The table's ranges, then what ties fields together.
void validateSettings(const AmbientOcclusionSettings& s) {
    obscura::validateSettings(AmbientOcclusionSettings::table(), s, "AmbientOcclusionSettings");
    if (s.method == AoMethod::Horizon && s.rays % 2 != 0)
        throw Error(ErrorCode::InvalidArgument, "AmbientOcclusionSettings::rays must be even for the horizon method "
                                                "(two directions per slice), got " + std::to_string(s.rays));
    if (s.method == AoMethod::Horizon && !s.cosineWeighted)
        throw Error(ErrorCode::InvalidArgument, "the horizon method integrates the cosine-weighted AO only: set "
                                                "AmbientOcclusionSettings::cosineWeighted");
    if (s.method == AoMethod::Horizon && s.falloff != ObscuranceFalloff::None)
        throw Error(ErrorCode::InvalidArgument, "the horizon method finds horizons, not hit distances, so it has no "
                                                "obscurance: set AmbientOcclusionSettings::falloff to None or use "
                                                "another method");
    if (s.method == AoMethod::Voxel) requireVoxelGrid(s.voxels, s.voxelTraversal, "AmbientOcclusionSettings");
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

// The run the settings ask for, on a view of `fullSize` (only the ray batches read it).
IntegratorShape shapeOf(const AmbientOcclusionSettings& s, glm::ivec2 fullSize) {
    // AO lies in [0, 1], background pixels 1.
    IntegratorShape shape = integratorShape(s, "ao", passName(s.method), AO_WORKGROUP, true, 1.0f);
    shape.direction = s.bentNormals;
    shape.batchItems = batchItems(s);
    shape.iterationsPerItem = iterationsPerItem(s, fullSize);
    shape.hiz = marchOf(s) == ScreenMarch::HiZ;
    shape.hizMode = thicknessOf(s);
    return shape;
}

} // namespace

struct AmbientOcclusion::Impl {
    explicit Impl(ContextImpl& c) : ctx(c) {}

    ContextImpl& ctx;
    ScreenIntegrator screen;
    Buffer params;

    shader::AoParams makeParams(const GBufferView& g, const AmbientOcclusionSettings& s, glm::ivec2 size, int scale) const {
        shader::AoParams p{};
        p.radius = s.radius;
        p.thickness = s.thickness > 0.0f ? s.thickness : s.radius;
        p.rayCount = s.rays;
        p.stepCount = s.steps;
        p.flags = (s.cosineWeighted ? AO_FLAG_COSINE : 0) | (s.bentNormals ? AO_FLAG_BENT : 0) | (filtered(s) ? AO_FLAG_GUIDE : 0);
        p.falloff = falloffCode(s.falloff);
        p.size = size;
        p.scale = scale;
        p.viewToVoxel = glm::mat4(1.0f);
        if (s.method == AoMethod::Voxel) {
            p.viewToVoxel = viewToVoxel(*s.voxels, g.camera);
            p.voxelStartOffset = static_cast<float>(voxelDiagonal(*s.voxels));
        }
        return p;
    }
};

AmbientOcclusion::AmbientOcclusion(Context& context) : impl_(std::make_unique<Impl>(context.impl())) {}
AmbientOcclusion::~AmbientOcclusion() = default;

AmbientOcclusionView AmbientOcclusion::run(const GBufferView& g, const AmbientOcclusionSettings& s) {
    validateSettings(s);
    auto& d = *impl_;
    auto& ctx = d.ctx;
    analyzeProjection(g.camera);
    const bool peeled = depthLayersFor(thicknessOf(s)) == 2;
    const GBufferView view = checkScreenInputs(ctx, g, peeled, "AmbientOcclusionSettings");
    const IntegratorShape shape = shapeOf(s, {view.width, view.height});
    // What this run writes (or reallocates): an earlier run's other outputs may be read.
    requireNotOwnOutput({{"GBufferView::depth", view.depth.name},
                         {"GBufferView::normal", view.normal.name},
                         {"GBufferView::backDepth", peeled ? view.backDepth.name : 0u}},
                        d.screen.written(shape), "AmbientOcclusion");

    StateScope scope(ctx);
    const shader::AoParams p = d.makeParams(view, s, ScreenIntegrator::reducedSize(view, shape.scale), shape.scale);
    uploadUniformBlock(ctx, d.params, p, AO_PARAMS_UBO_BINDING, "ao.params");
    d.screen.begin(ctx, view, peeled, s.frameIndex, shape);
    const IntegratorResult result = d.screen.run(
        ctx, view, shape, {AO_OUT_IMAGE, AO_BENT_OUT_IMAGE, AO_GUIDE_OUT_IMAGE},
        [&](const char* variant) { return integratorProgram(ctx, s, variant); },
        [&] {
            if (s.method == AoMethod::Voxel) bindVoxelGrid(ctx, *s.voxels);
        });
    return {result.value, result.direction, view.width, view.height};
}

void AmbientOcclusion::prepare(const AmbientOcclusionSettings& s) {
    validateSettings(s);
    auto& ctx = impl_->ctx;
    StateScope scope(ctx);
    ScreenIntegrator::prepare(ctx, shapeOf(s, {0, 0}), [&](const char* variant) { return integratorProgram(ctx, s, variant); });
}

void AmbientOcclusion::resetHistory() { impl_->screen.resetHistory(); }

RefinementCount AmbientOcclusion::lastRefinement() const { return impl_->screen.lastRefinement(impl_->ctx); }

std::size_t AmbientOcclusion::memoryBytes() const {
    const auto& d = *impl_;
    return d.screen.memoryBytes() + (d.params ? sizeof(shader::AoParams) : 0);
}

} // namespace obscura
