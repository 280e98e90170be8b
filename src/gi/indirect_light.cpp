#include "obscura/indirect_light.hpp"

#include "core/compute.hpp"
#include "core/context_impl.hpp"
#include "core/frame_uniforms.hpp"
#include "core/pass_scope.hpp"
#include "core/ray_batches.hpp"
#include "core/shader_library.hpp"
#include "core/texture_info.hpp"
#include "core/validate.hpp"
#include "filters/screen_integrator.hpp"
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
    obscura::validateSettings(IndirectLightSettings::table(), s, "IndirectLightSettings");
    if (s.method == GiMethod::Hybrid) requireVoxelGrid(s.voxels, s.voxelTraversal, "IndirectLightSettings");
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

// The run the settings ask for, on a view of `fullSize` (only the ray batches read it).
IntegratorShape shapeOf(const IndirectLightSettings& s, glm::ivec2 fullSize) {
    // Radiance, unbounded; background pixels 0.
    IntegratorShape shape = integratorShape(s, "gi", hybrid(s) ? "gi.hybrid" : "gi.screen", GI_WORKGROUP, false, 0.0f);
    shape.rgb = true;
    shape.batchItems = s.rays;
    shape.iterationsPerItem = hybrid(s) ? voxelRayIterations(*s.voxels, s.voxelTraversal, s.radius, s.steps) + 1
                                        : screenRayIterations(s.march, s.steps, fullSize);
    shape.hiz = !hybrid(s) && s.march == ScreenMarch::HiZ;
    shape.hizMode = thicknessOf(s);
    return shape;
}

} // namespace

struct IndirectLight::Impl {
    explicit Impl(ContextImpl& c) : ctx(c) {}

    ContextImpl& ctx;
    ScreenIntegrator screen;
    Buffer params;


    void uploadParams(const GBufferView& g, const IndirectLightSettings& s, glm::ivec2 size, int scale) {
        shader::GiParams p{};
        p.radius = s.radius;
        p.thickness = s.thickness > 0.0f ? s.thickness : s.radius;
        p.rayCount = s.rays;
        p.stepCount = s.steps;
        p.writeGuide = filtered(s) ? 1 : 0;
        p.size = size;
        p.scale = scale;
        p.viewToVoxel = glm::mat4(1.0f);
        if (s.method == GiMethod::Hybrid) {
            p.viewToVoxel = viewToVoxel(*s.voxels, g.camera);
            // As voxel AO: rays start about a voxel diagonal off the surface (plus the depth's
            // error and the normal bound, surface_rays.glsl); a voxel hit lies
            // within a voxel diagonal of the surface it stands for, so two diagonals is the
            // default tolerance for finding that surface on screen.
            p.voxelStartOffset = static_cast<float>(voxelDiagonal(*s.voxels));
            if (s.thickness <= 0.0f) p.thickness = 2.0f * p.voxelStartOffset;
        }
        uploadUniformBlock(ctx, params, p, GI_PARAMS_UBO_BINDING, "gi.params");
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
    const bool peeled = depthLayersFor(thicknessOf(s)) == 2;
    const GBufferView view = checkScreenInputs(ctx, g, peeled, "IndirectLightSettings");
    requireViewInput(ctx, g.albedo, view, "albedo", SampledAs::Rgb);
    requireViewInput(ctx, g.directRadiance, view, "directRadiance", SampledAs::Rgb);
    IntegratorShape shape = shapeOf(s, {view.width, view.height});
    shape.modulate = g.albedo.name;
    requireNotOwnOutput({{"GBufferView::depth", view.depth.name},
                         {"GBufferView::normal", view.normal.name},
                         {"GBufferView::backDepth", peeled ? view.backDepth.name : 0u},
                         {"GBufferView::albedo", g.albedo.name},
                         {"GBufferView::directRadiance", g.directRadiance.name}},
                        d.screen.written(shape), "IndirectLight"); // an earlier run's other output may be read

    StateScope scope(ctx);
    d.uploadParams(g, s, ScreenIntegrator::reducedSize(view, shape.scale), shape.scale);
    d.screen.begin(ctx, view, peeled, s.frameIndex, shape);
    bindNearest(ctx, GI_RADIANCE_UNIT, g.directRadiance.name);
    bindNearest(ctx, GI_ALBEDO_UNIT, g.albedo.name);
    const IntegratorResult result = d.screen.run(
        ctx, view, shape, {GI_OUT_IMAGE, GI_OUT_IMAGE, GI_GUIDE_OUT_IMAGE},
        [&](const char* variant) { return integratorProgram(ctx, s, variant); },
        [&] {
            if (hybrid(s)) bindVoxelGrid(ctx, *s.voxels);
        });
    return {result.value, view.width, view.height};
}

void IndirectLight::prepare(const IndirectLightSettings& s) {
    validateSettings(s);
    auto& ctx = impl_->ctx;
    StateScope scope(ctx);
    IntegratorShape shape = shapeOf(s, {0, 0});
    shape.modulate = 1; // the albedo: only that there is one matters here
    ScreenIntegrator::prepare(ctx, shape, [&](const char* variant) { return integratorProgram(ctx, s, variant); });
}

void IndirectLight::resetHistory() { impl_->screen.resetHistory(); }

RefinementCount IndirectLight::lastRefinement() const { return impl_->screen.lastRefinement(impl_->ctx); }

std::size_t IndirectLight::memoryBytes() const {
    const auto& d = *impl_;
    return d.screen.memoryBytes() + (d.params ? sizeof(shader::GiParams) : 0);
}

} // namespace obscura
