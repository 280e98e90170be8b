#include "obscura/directional_occlusion.hpp"

#include "core/context_impl.hpp"
#include "core/shader_library.hpp"
#include "core/texture_info.hpp"
#include "core/validate.hpp"
#include "core/compute.hpp"
#include "core/pass_scope.hpp"
#include "environment/environment_binding.hpp"
#include "gbuffer/light_records.hpp"
#include "shadows/shadow_lookup.hpp"
#include "filters/screen_integrator.hpp"
#include "visibility/screen_inputs.hpp"
#include "obscura/context.hpp"
#include "obscura/gbuffer.hpp"
#include "shaders/ssdo/ssdo_bindings.h"

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <array>
#include <optional>
#include <span>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

namespace obscura {
namespace {

using namespace detail;

constexpr double kPi = std::numbers::pi;

void validate(const DirectionalOcclusionSettings& s, const DirectionalOcclusionInputs& inputs) {
    validateSettings(DirectionalOcclusionSettings::table(), s, "DirectionalOcclusionSettings");
    if (s.extraViews > 0 && !inputs.scene)
        throw Error(ErrorCode::InvalidArgument, "DirectionalOcclusionSettings::extraViews needs "
                                                "DirectionalOcclusionInputs::scene (scene mode): a host G-buffer has no "
                                                "scene to render the views from");
    if (s.vplGrid > 0 && !(inputs.shadows && inputs.shadows->flux))
        throw Error(ErrorCode::InvalidArgument, "DirectionalOcclusionSettings::vplGrid needs reflective shadow maps: "
                                                "DirectionalOcclusionInputs::shadows rendered with "
                                                "ShadowMapSettings::reflective");
    if (!inputs.environment)
        throw Error(ErrorCode::InvalidArgument, "DirectionalOcclusionInputs::environment is required: SSDO lights the "
                                                "pixels with an EnvironmentMap");
}

// The extra views' cameras: the main camera's projection, eyes moved along its right and up
// axes by `offset` scene radii, looking at the point of its view axis nearest the scene's
// centre (or a radius ahead when the centre lies behind the eye).
std::vector<Camera> extraCameras(const Camera& main, const Bounds& bounds, int count, double offset) {
    const glm::dmat4 toWorld = glm::inverse(glm::dmat4(main.view));
    const glm::dvec3 eye(toWorld[3]), right = glm::normalize(glm::dvec3(toWorld[0]));
    const glm::dvec3 up = glm::normalize(glm::dvec3(toWorld[1])), forward = -glm::normalize(glm::dvec3(toWorld[2]));
    const glm::dvec3 centre = 0.5 * (glm::dvec3(bounds.min) + glm::dvec3(bounds.max));
    const double radius = 0.5 * glm::length(glm::dvec3(bounds.max) - glm::dvec3(bounds.min));
    double focus = glm::dot(centre - eye, forward);
    if (!(focus > 1e-3 * radius)) focus = radius;
    const glm::dvec3 target = eye + forward * focus;
    const std::array<glm::dvec3, 4> directions = {right, -right, up, -up};
    std::vector<Camera> cameras;
    for (int k = 0; k < count; ++k) {
        Camera c = main;
        c.view = glm::mat4(glm::lookAt(eye + directions[std::size_t(k)] * (offset * radius), target, up));
        cameras.push_back(c);
    }
    return cameras;
}

void validateLights(const DirectionalOcclusionInputs& inputs, const Camera& camera) {
    Scene lights; // validateScene's checks of each light
    lights.lights.assign(inputs.lights.begin(), inputs.lights.end());
    validateScene(lights);
    if (inputs.shadows)
        validateLightShadows(*inputs.shadows, inputs.shadowFilter, inputs.lights.size(), camera,
                             "DirectionalOcclusionInputs");
}

bool filtered(const DirectionalOcclusionSettings& s) { return filtersRun(static_cast<int>(s.resolution), s.blurRadius); }

GLuint integratorProgram(ContextImpl& ctx, const DirectionalOcclusionSettings& s, int pass, const char* variant) {
    std::vector<std::string> defines = {"PASS=" + std::to_string(pass)};
    const auto screen = screenMarchDefines(s.march, s.thicknessMode);
    defines.insert(defines.end(), screen.begin(), screen.end());
    if (s.extraViews > 0) defines.push_back("EXTRA_VIEWS");
    addRayLaneDefine(defines, s.rayLanes);
    if (variant) defines.push_back(variant);
    return ctx.shaders->program({"ssdo/ssdo.comp.glsl"}, defines);
}

// The direct pass ("ssdo") or the bounce ("ssdo_bounce": its own filters' names).
IntegratorShape shapeOf(const DirectionalOcclusionSettings& s, int pass, glm::ivec2 fullSize) {
    const bool direct = pass == SSDO_PASS_DIRECT;
    IntegratorShape shape = integratorShape(s, direct ? "ssdo" : "ssdo_bounce", direct ? "ssdo.direct" : "ssdo.bounce",
                                            SSDO_WORKGROUP, false, 0.0f);
    shape.rgb = true;
    shape.batchItems = s.rays;
    shape.iterationsPerItem = s.extraViews > 0 ? std::int64_t(s.steps) * (1 + s.extraViews) + (direct ? 0 : 4)
                                               : screenRayIterations(s.march, s.steps, fullSize) + (direct ? 0 : 4);
    // The bounce reuses the direct pass's pyramid; extra views march in view space.
    shape.hiz = direct && s.march == ScreenMarch::HiZ && s.extraViews == 0;
    shape.hizMode = s.thicknessMode;
    return shape;
}

} // namespace

struct DirectionalOcclusion::Impl {
    explicit Impl(ContextImpl& c) : ctx(c) {}

    ContextImpl& ctx;
    Context* context = nullptr;
    ScreenIntegrator direct, bounce;
    Buffer params, viewsBlock;
    LightRecords lights;
    SizedTexture lit, radiosity;
    Buffer vplsBlock;

    // Pass "ssdo.vpls": instant radiosity from the reflective maps, added to `bounce` (or
    // alone), at the G-buffer's resolution.
    TextureView addVpls(const GBufferView& view, const DirectionalOcclusionInputs& in, const DirectionalOcclusionSettings& s,
                        GLuint bounceTerm) {
        PassScope pass(ctx, "ssdo.vpls");
        const ShadowMapSet& maps = *in.shadows;
        shader::SsdoVpls v{};
        for (const ShadowMapInfo& m : maps.maps) {
            if (m.type != LightType::Spot && m.type != LightType::Directional) continue; // no reflective maps
            if (v.layerCount == SSDO_MAX_VPL_LAYERS) break;
            const int layer = m.type == LightType::Directional ? m.firstLayer + m.layers - 1 : m.firstLayer; // widest cascade
            v.layers[v.layerCount / 4][v.layerCount % 4] = layer;
            ++v.layerCount;
        }
        v.grid = std::min(s.vplGrid, maps.resolution);
        v.resolution = maps.resolution;
        uploadUniformBlock(ctx, vplsBlock, v, SSDO_VPLS_UBO_BINDING, "ssdo.vpls");
        current.contactThickness = in.shadowFilter.contactThickness;
        current.contactSteps = in.shadowFilter.contactSteps;
        uploadUniformBlock(ctx, params, current, SSDO_PARAMS_UBO_BINDING, "ssdo.params");
        std::vector<std::string> defines;
        if (bounceTerm) defines.push_back("BOUNCE");
        const auto screen = screenMarchDefines(s.march == ScreenMarch::HiZ ? ScreenMarch::Texture : s.march, s.thicknessMode);
        defines.insert(defines.end(), screen.begin(), screen.end());
        ctx.gl.UseProgram(ctx.shaders->program({"ssdo/ssdo_vpls.comp.glsl"}, defines));
        bindNearest(ctx, SSDO_RSM_FLUX_UNIT, maps.flux);
        bindNearest(ctx, SSDO_RSM_NORMAL_UNIT, maps.normal);
        bindNearest(ctx, SSDO_RSM_POSITION_UNIT, maps.position);
        if (bounceTerm) bindNearest(ctx, SSDO_INDIRECT_TERM_UNIT, bounceTerm);
        bindNearest(ctx, SSDO_ALBEDO_UNIT, view.albedo.name);
        const GLuint out = radiosity.ensure(ctx, GL_RGBA16F, view.width, view.height, "ssdo.indirect_vpl");
        ctx.state.bindImage(ctx, SSDO_OUT_IMAGE, out, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA16F);
        dispatchCompute2D(ctx, view.width, view.height, SSDO_WORKGROUP);
        barrierForReaders(ctx);
        return {out, GL_RGBA16F, view.width, view.height};
    }
    std::unique_ptr<GBuffer> views; // the extra views' G-buffers, one after another
    Texture viewDepth, viewNormal;  // their depth and normals, a layer each
    glm::ivec3 viewArraySize{0};
    shader::SsdoViews viewData{};

    // Pass "ssdo.views": renders the extra views (GBuffer::render, whose StateScope nests in
    // the run's) and copies each into the layer arrays.
    void renderViews(const GBufferView& g, const Scene& scene, const DirectionalOcclusionSettings& s) {
        const Bounds bounds = sceneBounds(scene);
        if (bounds.empty)
            throw Error(ErrorCode::InvalidArgument, "DirectionalOcclusionSettings::extraViews: the scene has no CPU "
                                                    "meshes to place the views around");
        if (!views) views = std::make_unique<GBuffer>(*context);
        const int w = std::max(1, int(std::ceil(g.width * double(s.extraViewScale))));
        const int h = std::max(1, int(std::ceil(g.height * double(s.extraViewScale))));
        const std::vector<Camera> cameras = extraCameras(g.camera, bounds, s.extraViews, s.extraViewOffset);
        GBufferSettings settings;
        settings.width = w;
        settings.height = h;
        settings.directLighting = false;
        const glm::dmat4 mainToWorld = glm::inverse(glm::dmat4(g.camera.view));
        viewData = {};
        for (int k = 0; k < s.extraViews; ++k) {
            const GBufferView v = views->render(scene, cameras[std::size_t(k)], settings);
            ensureViewArrays(w, h, s.extraViews);
            ctx.gl.CopyImageSubData(v.depth.name, GL_TEXTURE_2D, 0, 0, 0, 0, viewDepth.get(), GL_TEXTURE_2D_ARRAY, 0, 0, 0, k,
                                    w, h, 1);
            ctx.gl.CopyImageSubData(v.normal.name, GL_TEXTURE_2D, 0, 0, 0, 0, viewNormal.get(), GL_TEXTURE_2D_ARRAY, 0, 0, 0,
                                    k, w, h, 1);
            viewData.mainToView[k] = glm::mat4(glm::dmat4(cameras[std::size_t(k)].view) * mainToWorld);
        }
        viewData.size = {w, h};
        viewData.count = s.extraViews;
    }

    void ensureViewArrays(int w, int h, int layers) {
        if (viewDepth && viewArraySize == glm::ivec3(w, h, layers)) return;
        viewDepth = createTexture2DArray(ctx, GL_DEPTH_COMPONENT32F, w, h, layers, "ssdo.view_depth");
        viewNormal = createTexture2DArray(ctx, GL_RGBA16F, w, h, layers, "ssdo.view_normal");
        viewArraySize = {w, h, layers};
    }

    void bindViews() {
        uploadUniformBlock(ctx, viewsBlock, viewData, SSDO_VIEWS_UBO_BINDING, "ssdo.views");
        bindNearest(ctx, SSDO_EXTRA_DEPTH_UNIT, viewDepth.get());
        bindNearest(ctx, SSDO_EXTRA_NORMAL_UNIT, viewNormal.get());
    }

    void releaseViews() {
        views.reset();
        viewDepth.reset();
        viewNormal.reset();
        viewArraySize = glm::ivec3(0);
    }

    // Pass "ssdo.lights": the environment term plus the lights, at the G-buffer's resolution.
    TextureView addLights(const GBufferView& view, const DirectionalOcclusionInputs& in,
                          const DirectionalOcclusionSettings& s, GLuint environmentTerm) {
        PassScope pass(ctx, "ssdo.lights");
        const bool shadowed = lights.bindShadows(ctx, in.lights, view.camera, in.shadows, in.shadowFilter);
        lights.upload(ctx, in.lights, glm::dmat4(view.camera.view), "ssdo.lights");
        current.lightCount = static_cast<int>(in.lights.size());
        current.shadowCorrection = s.shadowCorrection;
        current.contactThickness = in.shadowFilter.contactThickness;
        current.contactSteps = in.shadowFilter.contactSteps;
        uploadUniformBlock(ctx, params, current, SSDO_PARAMS_UBO_BINDING, "ssdo.params");
        std::vector<std::string> defines;
        if (std::any_of(in.lights.begin(), in.lights.end(), [](const Light& l) { return l.type == LightType::Rect; }))
            defines.push_back("RECT_LIGHTS");
        if (shadowed) {
            defines.insert(defines.end(), {"SHADOWS", shadowFilterDefine(in.shadowFilter.filter)});
            if (s.shadowCorrection > 0.0f) {
                defines.push_back("CORRECTION");
                const auto screen = screenMarchDefines(s.march == ScreenMarch::HiZ ? ScreenMarch::Texture : s.march, s.thicknessMode);
                defines.insert(defines.end(), screen.begin(), screen.end());
            }
        }
        ctx.gl.UseProgram(ctx.shaders->program({"ssdo/ssdo_lights.comp.glsl"}, defines));
        bindNearest(ctx, SSDO_ENVIRONMENT_TERM_UNIT, environmentTerm);
        bindNearest(ctx, SSDO_ALBEDO_UNIT, view.albedo.name);
        const GLuint out = lit.ensure(ctx, GL_RGBA16F, view.width, view.height, "ssdo.direct_lit");
        ctx.state.bindImage(ctx, SSDO_OUT_IMAGE, out, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA16F);
        dispatchCompute2D(ctx, view.width, view.height, SSDO_WORKGROUP);
        barrierForReaders(ctx); // the bounce's senders, or the host: `direct` as returned
        return {out, GL_RGBA16F, view.width, view.height};
    }


    void uploadParams(const GBufferView& g, const DirectionalOcclusionSettings& s, glm::ivec2 size, int scale) {
        shader::SsdoParams p{};
        p.radius = s.radius;
        p.thickness = s.thickness > 0.0f ? s.thickness : s.radius;
        p.patchArea = static_cast<float>(kPi * double(s.radius) * double(s.radius) / s.rays);
        p.patchSolidAngle = static_cast<float>(2.0 * kPi * (1.0 - 1.0 / std::sqrt(2.0)));
        p.rayCount = s.rays;
        p.stepCount = s.steps;
        p.writeGuide = filtered(s) ? 1 : 0;
        p.addLight = g.directRadiance ? 1 : 0;
        p.size = size;
        p.scale = scale;
        p.bounceStrength = s.bounceStrength;
        p.environmentLevel = 0.0f; // set by the caller from the environment
        p.viewToWorld = glm::mat4(glm::mat3(glm::inverse(g.camera.view)));
        current = p;
    }

    shader::SsdoParams current{};
};

DirectionalOcclusion::DirectionalOcclusion(Context& context) : impl_(std::make_unique<Impl>(context.impl())) {
    impl_->context = &context;
}
DirectionalOcclusion::~DirectionalOcclusion() = default;

DirectionalOcclusionView DirectionalOcclusion::run(const GBufferView& g, const DirectionalOcclusionInputs& inputs,
                                                   const DirectionalOcclusionSettings& s) {
    validate(s, inputs);
    auto& d = *impl_;
    auto& ctx = d.ctx;
    analyzeProjection(g.camera);
    validateLights(inputs, g.camera);
    if (!g.albedo)
        throw Error(ErrorCode::InvalidArgument, "SSDO multiplies by the G-buffer's albedo: render the G-buffer with "
                                                "GBuffer::render, or give HostGBuffer::albedo to GBuffer::adopt");
    const bool peeled = depthLayersFor(s.thicknessMode) == 2;
    const GBufferView view = checkScreenInputs(ctx, g, peeled, "DirectionalOcclusionSettings");
    requireViewInput(ctx, g.albedo, view, "albedo", SampledAs::Rgb);
    if (g.directRadiance) requireViewInput(ctx, g.directRadiance, view, "directRadiance", SampledAs::Rgb);
    IntegratorShape directShape = shapeOf(s, SSDO_PASS_DIRECT, {view.width, view.height});
    IntegratorShape bounceShape = shapeOf(s, SSDO_PASS_BOUNCE, {view.width, view.height});
    directShape.modulate = bounceShape.modulate = g.albedo.name;
    std::vector<GLuint> written = d.direct.written(directShape);
    if (!inputs.lights.empty()) written.push_back(d.lit.get());
    if (s.vplGrid > 0) written.push_back(d.radiosity.get());
    if (s.bounce) {
        const auto more = d.bounce.written(bounceShape);
        written.insert(written.end(), more.begin(), more.end());
    }
    requireNotOwnOutput({{"GBufferView::depth", view.depth.name},
                         {"GBufferView::normal", view.normal.name},
                         {"GBufferView::backDepth", peeled ? view.backDepth.name : 0u},
                         {"GBufferView::albedo", g.albedo.name},
                         {"GBufferView::directRadiance", g.directRadiance.name}},
                        written, "DirectionalOcclusion");

    StateScope scope(ctx); // nests GBuffer::render's own for the extra views
    if (s.extraViews > 0) {
        PassScope pass(ctx, "ssdo.views");
        d.renderViews(view, *inputs.scene, s);
    } else {
        d.releaseViews(); // not asked for: not kept
    }
    const glm::ivec2 size = ScreenIntegrator::reducedSize(view, directShape.scale);
    d.uploadParams(g, s, size, directShape.scale);
    const EnvironmentView env = inputs.environment->view();
    // A sample stands for 2 pi / rays of the hemisphere: the level whose texels are about that
    // big, a whole one, because filtering between two levels weighs them in fixed point (on
    // llvmpipe a constant environment came out 0.12 % dark at level 1.79).
    const double texel = 4.0 * kPi / (6.0 * double(env.cubeSize) * double(env.cubeSize));
    d.current.environmentLevel = !s.prefilter ? 0.0f : static_cast<float>(std::round(
        std::clamp(0.5 * std::log2(std::max(2.0 * kPi / s.rays / texel, 1.0)), 0.0, double(env.cubeLevels - 1))));
    uploadUniformBlock(ctx, d.params, d.current, SSDO_PARAMS_UBO_BINDING, "ssdo.params");
    d.direct.begin(ctx, view, peeled, s.frameIndex, directShape);
    EnvironmentBinding::bind(ctx, *inputs.environment);
    if (s.extraViews > 0) d.bindViews();
    bindNearest(ctx, SSDO_ALBEDO_UNIT, g.albedo.name);
    const IntegratorImages images{SSDO_OUT_IMAGE, SSDO_OUT_IMAGE, SSDO_GUIDE_OUT_IMAGE};
    const IntegratorResult direct = d.direct.run(
        ctx, view, directShape, images, [&](const char* v) { return integratorProgram(ctx, s, SSDO_PASS_DIRECT, v); },
        [] {});
    DirectionalOcclusionView out{direct.value, {}, view.width, view.height};
    if (!inputs.lights.empty()) out.direct = d.addLights(view, inputs, s, direct.value.name);
    else d.lit.release(); // not asked for: not kept
    if (s.bounce) {
        d.bounce.begin(ctx, view, peeled, s.frameIndex, bounceShape);
        if (s.extraViews > 0) d.bindViews();
        bindNearest(ctx, SSDO_ALBEDO_UNIT, g.albedo.name);
        // With VPLs the lights' bounce is theirs: the senders carry the environment's light.
        bindNearest(ctx, SSDO_SENDER_UNIT, s.vplGrid > 0 ? direct.value.name : out.direct.name);
        if (g.directRadiance) bindNearest(ctx, SSDO_LIGHT_UNIT, g.directRadiance.name);
        ctx.state.bindUniformBuffer(ctx, SSDO_PARAMS_UBO_BINDING, d.params.get());
        out.indirect = d.bounce.run(ctx, view, bounceShape, images,
                                    [&](const char* v) { return integratorProgram(ctx, s, SSDO_PASS_BOUNCE, v); }, [] {})
                           .value;
    } else {
        d.bounce.resetHistory();
    }
    if (s.vplGrid > 0) out.indirect = d.addVpls(view, inputs, s, out.indirect.name);
    else d.radiosity.release(); // not asked for: not kept
    return out;
}

void DirectionalOcclusion::prepare(const DirectionalOcclusionSettings& s) {
    validateSettings(DirectionalOcclusionSettings::table(), s, "DirectionalOcclusionSettings");
    auto& ctx = impl_->ctx;
    StateScope scope(ctx);
    for (int pass : {SSDO_PASS_DIRECT, SSDO_PASS_BOUNCE}) {
        if (pass == SSDO_PASS_BOUNCE && !s.bounce) continue;
        IntegratorShape shape = shapeOf(s, pass, {0, 0});
        shape.modulate = 1; // the albedo: only that there is one matters here
        ScreenIntegrator::prepare(ctx, shape, [&](const char* v) { return integratorProgram(ctx, s, pass, v); });
    }
}

RefinementCount DirectionalOcclusion::lastRefinement() const {
    const RefinementCount a = impl_->direct.lastRefinement(impl_->ctx), b = impl_->bounce.lastRefinement(impl_->ctx);
    return {a.asked + b.asked, a.refined + b.refined};
}

void DirectionalOcclusion::resetHistory() {
    impl_->direct.resetHistory();
    impl_->bounce.resetHistory();
}

std::size_t DirectionalOcclusion::memoryBytes() const {
    const auto& d = *impl_;
    const std::size_t viewTexels = std::size_t(d.viewArraySize.x) * std::size_t(d.viewArraySize.y) * std::size_t(d.viewArraySize.z);
    return d.direct.memoryBytes() + d.bounce.memoryBytes() + d.lights.memoryBytes() + d.lit.bytes() + d.radiosity.bytes() +
           (d.vplsBlock ? sizeof(shader::SsdoVpls) : 0) +
           (d.views ? d.views->memoryBytes() : 0) + viewTexels * (bytesPerTexel(GL_DEPTH_COMPONENT32F) + bytesPerTexel(GL_RGBA16F)) +
           (d.viewsBlock ? sizeof(shader::SsdoViews) : 0) +
           (d.params ? sizeof(shader::SsdoParams) : 0);
}

} // namespace obscura
