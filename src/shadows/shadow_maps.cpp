#include "obscura/shadow_maps.hpp"

#include "core/compute.hpp"
#include "core/context_impl.hpp"
#include "core/frame_uniforms.hpp"
#include "core/texture_info.hpp"
#include "core/mesh_cache.hpp"
#include "core/pass_scope.hpp"
#include "core/shader_library.hpp"
#include "core/validate.hpp"
#include "obscura/context.hpp"
#include "obscura/error.hpp"
#include "shaders/shadows/shadow_bindings.h"
#include "shadows/light_frusta.hpp"
#include "shadows/shadow_lookup.hpp"
#include "visibility/screen_inputs.hpp"

#include <glm/gtc/type_ptr.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <optional>
#include <string>

namespace obscura {
namespace {

using namespace detail;

void validateSettings(const ShadowMapSettings& s, int maxTextureSize) {
    obscura::validateSettings(ShadowMapSettings::table(), s, "ShadowMapSettings");
    static_assert(kMaxShadowCascades == 4, "the table's cascades range");
    const double largest = findSetting(ShadowMapSettings::table(), "resolution")->max; // the table's bound
    requireInRange(s.resolution, 16, std::min(largest, double(maxTextureSize)), "ShadowMapSettings::resolution", "texels");
}

glm::dmat4 worldToClip(const Camera& c) { return glm::dmat4(c.projection) * glm::dmat4(c.view); }

// One layer of the maps' array as the depth pass draws it: a world -> clip transform, or
// (paraboloid) world -> the map's frame and the distance -> depth mapping.
struct MapLayer {
    glm::dmat4 transform{1.0};
    bool paraboloid = false;
    glm::vec2 depthAB{0.0f};
    const Light* reflective = nullptr; //!< the light, when this layer gets a reflective shadow map
    float texelSize = 0.0f;            //!< ShadowMapInfo::texelSize of the layer
};

// Window depth (clip control zero-to-one: z_ndc) back to distance along the map's axis:
// perspective z_ndc = (A z + B) / -z, orthographic z_ndc = A z + B, z = -distance.
glm::vec4 depthMapping(const Camera& c) {
    const ProjectionInfo info = analyzeProjection(c);
    const glm::dmat4 p(c.projection);
    return glm::vec4(static_cast<float>(p[2][2]), static_cast<float>(p[3][2]), info.nearPlane, info.farPlane);
}

} // namespace

bool hasShadowMaps(const Light& l) { return l.castsShadows; }

const ShadowMapInfo* ShadowMapSet::find(std::size_t light) const {
    for (const ShadowMapInfo& m : maps)
        if (m.light == light) return &m;
    return nullptr;
}

struct ShadowMaps::Impl {
    explicit Impl(ContextImpl& c) : ctx(c), meshes(c) {}

    ContextImpl& ctx;
    MeshCache meshes;
    Texture depth;
    int depthResolution = 0, depthLayers = 0;
    Framebuffer fbo;
    FrameUniforms frame;
    ShadowBinding binding;
    Texture moments, momentsTemp; // arrays with the maps' layers, for the moment filters
    GLenum momentsFormat = GL_NONE; // theirs (shadowMomentFormat)
    Buffer rangeBuffer;           // depth_range.comp.glsl's result
    Texture flux, normal, position; // reflective shadow maps (ShadowMapSettings::reflective)
    SizedTexture maskTexture;
    ShadowMapSet set;

    // The maps' layers, and what the mask pass needs to know of them.
    std::vector<MapLayer> plan(const Scene& scene, const Camera& camera, const ShadowMapSettings& s,
                               const std::optional<DistanceRange>& depthRange) {
        const Bounds bounds = sceneBounds(scene);
        std::vector<MapLayer> cameras;
        const auto addCamera = [&](ShadowMapInfo& info, std::size_t k, const LightCamera& lc) {
            const Light& l = scene.lights[info.light];
            const bool rsm = s.reflective && (l.type == LightType::Spot || l.type == LightType::Directional);
            cameras.push_back({worldToClip(lc.camera), false, {}, rsm ? &l : nullptr, static_cast<float>(lc.texelSize)});
            info.worldToClip[k] = glm::mat4(cameras.back().transform);
            info.texelSize[k] = static_cast<float>(lc.texelSize);
            info.depthMapping[k] = depthMapping(lc.camera);
        };
        set.maps.clear();
        for (std::size_t i = 0; i < scene.lights.size(); ++i) {
            const Light& l = scene.lights[i];
            if (!hasShadowMaps(l)) continue;
            if (bounds.empty)
                throw Error(ErrorCode::InvalidArgument, "ShadowMaps::render: the scene has no CPU meshes to fit the maps to");
            ShadowMapInfo info;
            info.light = i;
            info.source = l;
            info.type = l.type;
            info.firstLayer = static_cast<int>(cameras.size());
            const bool point = l.type == LightType::Point || l.type == LightType::Sphere; // mapped from its centre
            const auto addParaboloid = [&](const ParaboloidMap& pm) {
                const auto k = static_cast<std::size_t>(info.layers++);
                cameras.push_back({pm.worldToMap, true, glm::vec2(pm.depthMapping), nullptr, 0.0f});
                info.worldToClip[k] = glm::mat4(pm.worldToMap);
                info.texelSize[k] = static_cast<float>(pm.texelSize);
                info.depthMapping[k] = glm::vec4(pm.depthMapping);
                info.paraboloid = true;
            };
            if (point && s.pointMapping == PointShadowMapping::DualParaboloid) {
                for (int h = 0; h < 2; ++h) addParaboloid(paraboloidHemisphere(l, h, bounds, s.resolution));
            } else if (l.type == LightType::Rect) {
                addParaboloid(rectParaboloid(l, bounds, s.resolution)); // it emits toward one side only
            } else if (point) {
                // Room for the widest PCF kernel (8 texels each side, plus the bilinear one).
                const int margin = std::min(9, s.resolution / 8);
                for (int face = 0; face < 6; ++face)
                    addCamera(info, static_cast<std::size_t>(face), pointFace(l, face, bounds, s.resolution, margin));
                info.layers = 6;
            } else if (l.type == LightType::Spot) {
                addCamera(info, 0, spotCamera(l, bounds, s.resolution));
                info.layers = 1;
            } else {
                const DistanceRange range = depthRange ? *depthRange : visibleDistances(camera, bounds);
                const std::vector<double> ends = cascadeSplits(range.nearest, range.farthest, s.cascades, s.splitLambda);
                double from = range.nearest;
                info.sliceStart = static_cast<float>(range.nearest);
                for (int c = 0; c < s.cascades; ++c) {
                    const auto k = static_cast<std::size_t>(c);
                    addCamera(info, k, directionalCascade(glm::dvec3(l.direction), camera, from, ends[k], bounds, s.resolution));
                    info.sliceEnd[k] = static_cast<float>(ends[k]);
                    from = ends[k];
                }
                info.layers = s.cascades;
            }
            set.maps.push_back(info);
        }
        return cameras;
    }

    // The moments of `info`'s maps, prefiltered (pass "shadow.moments"), bound at
    // SHADOW_MOMENTS_UNIT; the light's record must be bound already.
    void prepareMoments(const ShadowMapInfo& info, const ShadowMaskSettings& s) {
        auto& gl = ctx.gl;
        PassScope pass(ctx, "shadow.moments");
        const GLenum format = shadowMomentFormat(s);
        if (!moments || momentsFormat != format) {
            moments = createTexture2DArray(ctx, format, depthResolution, depthResolution, depthLayers, "shadow.moments");
            momentsTemp = createTexture2DArray(ctx, format, depthResolution, depthResolution, depthLayers, "shadow.moments_temp");
            momentsFormat = format;
        }
        const Defines filter = shadowMaskDefines(s);
        GLuint program = ctx.shaders->program({"shadows/shadow_moments.comp.glsl"}, filter);
        gl.UseProgram(program);
        gl.ProgramUniform2i(program, SHADOW_LOC_LAYER_RANGE, info.firstLayer, info.layers);
        ctx.state.bindTexture(ctx, SHADOW_DEPTH_READ_UNIT, depth.get());
        ctx.state.bindSampler(ctx, SHADOW_DEPTH_READ_UNIT, ctx.nearestClampSampler());
        ctx.state.bindImage(ctx, SHADOW_MOMENTS_IMAGE, moments.get(), 0, GL_TRUE, 0, GL_WRITE_ONLY, format);
        const GLuint groups = static_cast<GLuint>((depthResolution + SHADOW_WORKGROUP - 1) / SHADOW_WORKGROUP);
        gl.DispatchCompute(groups, groups, static_cast<GLuint>(info.layers));
        if (s.momentBlur > 0) {
            // ESM's log-space moment has its own blur; the others are plain averages.
            Defines blur = filter; // the storage's define after the filter's
            blur[0] = "FILTER=" + std::to_string(s.filter == ShadowFilter::Esm ? SHADOW_FILTER_ESM : SHADOW_FILTER_VSM);
            program = ctx.shaders->program({"shadows/shadow_moments_blur.comp.glsl"}, blur);
            gl.UseProgram(program);
            gl.ProgramUniform2i(program, SHADOW_LOC_LAYER_RANGE, info.firstLayer, info.layers);
            for (int direction = 0; direction < 2; ++direction) {
                const GLuint from = direction == 0 ? moments.get() : momentsTemp.get();
                const GLuint to = direction == 0 ? momentsTemp.get() : moments.get();
                gl.MemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
                gl.ProgramUniform2i(program, SHADOW_LOC_FILTER_PARAMS, s.momentBlur, direction);
                ctx.state.bindImage(ctx, SHADOW_MOMENTS_READ_IMAGE, from, 0, GL_TRUE, 0, GL_READ_ONLY, format);
                ctx.state.bindImage(ctx, SHADOW_MOMENTS_IMAGE, to, 0, GL_TRUE, 0, GL_WRITE_ONLY, format);
                gl.DispatchCompute(groups, groups, static_cast<GLuint>(info.layers));
            }
        }
        gl.MemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT);
        ctx.state.bindTexture(ctx, SHADOW_MOMENTS_UNIT, moments.get());
        ctx.state.bindSampler(ctx, SHADOW_MOMENTS_UNIT, ctx.linearClampSampler());
    }

    // The nearest and farthest view distance of the view's geometry pixels, if it has any.
    std::optional<DistanceRange> measureDepthRange(const GBufferView& g, const Camera& camera) {
        auto& gl = ctx.gl;
        if (!(g.camera.view == camera.view && g.camera.projection == camera.projection && g.camera.clipDepth == camera.clipDepth))
            throw Error(ErrorCode::InvalidArgument, "ShadowMaps::render: the depth view is of another camera");
        const GBufferView view = checkScreenInputs(ctx, g, false, "ShadowMaps::render");
        StateScope scope(ctx);
        PassScope pass(ctx, "shadow.depth_range");
        const GLuint init[2] = {0x7f800000u, 0u}; // +inf, 0
        if (!rangeBuffer) rangeBuffer = createBuffer(ctx, sizeof init, nullptr, GL_DYNAMIC_STORAGE_BIT, "shadow.depth_range");
        gl.NamedBufferSubData(rangeBuffer.get(), 0, sizeof init, init);
        ctx.state.bindStorageBuffer(ctx, SHADOW_RANGE_SSBO, rangeBuffer.get());
        frame.bind(ctx, view.camera, view.width, view.height, depthStepOf(ctx, view.depth.name), view.normalError);
        bindScreenInputs(ctx, view, false);
        gl.UseProgram(ctx.shaders->program({"shadows/depth_range.comp.glsl"}));
        dispatchCompute2D(ctx, view.width, view.height, SHADOW_WORKGROUP);
        gl.MemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
        GLuint bits[2] = {0u, 0u};
        gl.GetNamedBufferSubData(rangeBuffer.get(), 0, sizeof bits, bits);
        if (bits[1] == 0u) return std::nullopt; // no geometry
        float nearest = 0.0f, farthest = 0.0f;
        std::memcpy(&nearest, &bits[0], sizeof nearest);
        std::memcpy(&farthest, &bits[1], sizeof farthest);
        const ProjectionInfo info = analyzeProjection(camera);
        // A single depth (one flat wall facing the camera) still needs a slice of some width.
        return DistanceRange{nearest, std::max(double(farthest), nearest * (1.0 + 1e-3) + info.nearPlane * 1e-3)};
    }

    void ensureDepth(int resolution, int layers) {
        if (depth && resolution == depthResolution && layers == depthLayers) return;
        depth = createTexture2DArray(ctx, GL_DEPTH_COMPONENT32F, resolution, resolution, layers, "shadow.maps");
        depthResolution = resolution;
        depthLayers = layers;
        moments.reset(); // reallocated at the maps' size when a moment filter asks
        momentsFormat = GL_NONE;
        momentsTemp.reset();
        flux.reset(); // reallocated when reflective maps are asked for
        normal.reset();
        position.reset();
        if (!fbo) fbo = createFramebuffer(ctx, "shadow.maps");
    }

    const ShadowMapSet& render(const Scene& scene, const Camera& camera, const ShadowMapSettings& settings,
                               const std::optional<DistanceRange>& depthRange);

    void ensureReflective() {
        if (flux) return;
        flux = createTexture2DArray(ctx, GL_RGBA16F, depthResolution, depthResolution, depthLayers, "shadow.rsm_flux");
        normal = createTexture2DArray(ctx, GL_RGBA16F, depthResolution, depthResolution, depthLayers, "shadow.rsm_normal");
        position = createTexture2DArray(ctx, GL_RGBA32F, depthResolution, depthResolution, depthLayers, "shadow.rsm_position");
        const float zero[4] = {0.0f, 0.0f, 0.0f, 0.0f};
        for (const Texture* t : {&flux, &normal, &position}) ctx.gl.ClearTexImage(t->get(), 0, GL_RGBA, GL_FLOAT, zero);
    }

    // Binds layer `layer` of the reflective maps as colour attachments 0..2 and clears them.
    void attachReflective(GLint layer) {
        auto& gl = ctx.gl;
        const GLenum buffers[3] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1, GL_COLOR_ATTACHMENT2};
        gl.NamedFramebufferTextureLayer(fbo.get(), GL_COLOR_ATTACHMENT0, flux.get(), 0, layer);
        gl.NamedFramebufferTextureLayer(fbo.get(), GL_COLOR_ATTACHMENT1, normal.get(), 0, layer);
        gl.NamedFramebufferTextureLayer(fbo.get(), GL_COLOR_ATTACHMENT2, position.get(), 0, layer);
        gl.NamedFramebufferDrawBuffers(fbo.get(), 3, buffers);
        const float zero[4] = {0.0f, 0.0f, 0.0f, 0.0f};
        for (GLint i = 0; i < 3; ++i) gl.ClearNamedFramebufferfv(fbo.get(), GL_COLOR, i, zero);
    }

    // The depth and reflective maps of one spot or directional layer in one set of draws.
    void drawReflective(const Scene& scene, const MapLayer& target, const std::vector<DrawableMesh>& hostMeshes) {
        auto& gl = ctx.gl;
        const GLuint program = ctx.shaders->program({"shadows/shadow_rsm.vert.glsl", "shadows/shadow_rsm.frag.glsl"});
        gl.UseProgram(program);
        const Light& l = *target.reflective;
        const bool spot = l.type == LightType::Spot;
        const glm::vec3 axis = glm::normalize(l.direction);
        const glm::vec3 where = spot ? l.position : axis;
        gl.ProgramUniform4f(program, SHADOW_LOC_RSM_LIGHT, where.x, where.y, where.z, spot ? SHADOW_LIGHT_SPOT : SHADOW_LIGHT_DIRECTIONAL);
        const glm::vec3 power = l.color * l.intensity;
        gl.ProgramUniform4f(program, SHADOW_LOC_RSM_POWER, power.x, power.y, power.z, target.texelSize);
        gl.ProgramUniform4f(program, SHADOW_LOC_RSM_SPOT, axis.x, axis.y, axis.z, 0.0f);
        gl.ProgramUniform2f(program, SHADOW_LOC_RSM_CONE, std::cos(l.innerAngle), std::cos(l.outerAngle));
        const auto draw = [&](const DrawableMesh& mesh, const glm::mat4& model, std::uint32_t material) {
            const glm::mat4 m(target.transform * glm::dmat4(model));
            gl.ProgramUniformMatrix4fv(program, SHADOW_LOC_MODEL_LIGHT_CLIP, 1, GL_FALSE, glm::value_ptr(m));
            gl.ProgramUniformMatrix4fv(program, SHADOW_LOC_RSM_MODEL, 1, GL_FALSE, glm::value_ptr(model));
            const glm::vec3 albedo = scene.materials.at(material).albedo;
            gl.ProgramUniform3f(program, SHADOW_LOC_RSM_ALBEDO, albedo.x, albedo.y, albedo.z);
            drawMesh(ctx, mesh);
        };
        for (const Mesh& mesh : scene.meshes) {
            const DrawableMesh d = meshes.cpuMesh(mesh.data);
            if (d.count > 0) draw(d, mesh.model, mesh.material);
        }
        for (std::size_t i = 0; i < scene.meshRefs.size(); ++i) draw(hostMeshes[i], scene.meshRefs[i].model, scene.meshRefs[i].material);
        gl.NamedFramebufferDrawBuffer(fbo.get(), GL_NONE);
        for (GLenum a : {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1, GL_COLOR_ATTACHMENT2}) gl.NamedFramebufferTexture(fbo.get(), a, 0, 0);
    }

    void drawMaps(const Scene& scene, const std::vector<MapLayer>& cameras) {
        auto& gl = ctx.gl;
        std::vector<DrawableMesh> hostMeshes; // first: reading a host VAO's layout binds it
        for (std::size_t i = 0; i < scene.meshRefs.size(); ++i) hostMeshes.push_back(meshes.hostMesh(i, scene.meshRefs[i]));
        gl.BindFramebuffer(GL_FRAMEBUFFER, fbo.get());
        gl.NamedFramebufferDrawBuffer(fbo.get(), GL_NONE);
        setViewport(ctx, 0, 0, depthResolution, depthResolution);
        // Reversed-Z: nearer is greater; depth clamp keeps casters in front of the near plane.
        applyDrawState(ctx, {true, true, GL_GREATER, false, false, GL_ZERO_TO_ONE, true});
        const float clearDepth = 0.0f;
        for (std::size_t layer = 0; layer < cameras.size(); ++layer) {
            gl.NamedFramebufferTextureLayer(fbo.get(), GL_DEPTH_ATTACHMENT, depth.get(), 0, static_cast<GLint>(layer));
            gl.ClearNamedFramebufferfv(fbo.get(), GL_DEPTH, 0, &clearDepth);
            const MapLayer& target = cameras[layer];
            if (target.reflective) {
                attachReflective(static_cast<GLint>(layer));
                drawReflective(scene, target, hostMeshes);
                continue;
            }
            const GLuint program = target.paraboloid ? ctx.shaders->program({"shadows/shadow_paraboloid.vert.glsl",
                                                                              "shadows/shadow_paraboloid.geom.glsl",
                                                                              "shadows/shadow_paraboloid.frag.glsl"})
                                                     : ctx.shaders->program({"shadows/shadow_depth.vert.glsl",
                                                                              "shadows/shadow_depth.frag.glsl"});
            gl.UseProgram(program);
            if (target.paraboloid)
                gl.ProgramUniform3f(program, SHADOW_LOC_PARABOLOID_DEPTH, target.depthAB.x, target.depthAB.y,
                                    2.0f / static_cast<float>(depthResolution));
            const glm::dmat4& lightClip = target.transform;
            const auto draw = [&](const DrawableMesh& mesh, const glm::mat4& model) {
                const glm::mat4 m(lightClip * glm::dmat4(model));
                gl.ProgramUniformMatrix4fv(program, SHADOW_LOC_MODEL_LIGHT_CLIP, 1, GL_FALSE, glm::value_ptr(m));
                drawMesh(ctx, mesh);
            };
            for (const Mesh& mesh : scene.meshes) {
                const DrawableMesh d = meshes.cpuMesh(mesh.data);
                if (d.count > 0) draw(d, mesh.model);
            }
            for (std::size_t i = 0; i < scene.meshRefs.size(); ++i) draw(hostMeshes[i], scene.meshRefs[i].model);
        }
    }
};

ShadowMaps::ShadowMaps(Context& context) : impl_(std::make_unique<Impl>(context.impl())) {}
ShadowMaps::~ShadowMaps() = default;

const ShadowMapSet& ShadowMaps::render(const Scene& scene, const Camera& camera, const ShadowMapSettings& settings) {
    return impl_->render(scene, camera, settings, std::nullopt);
}

const ShadowMapSet& ShadowMaps::render(const Scene& scene, const Camera& camera, const ShadowMapSettings& settings,
                                       const GBufferView& depth) {
    auto& d = *impl_;
    validateSettings(settings, d.ctx.info.maxTextureSize);
    analyzeProjection(camera);
    // Only cascades use the range: without a shadowed directional light, nothing to measure.
    const bool cascaded = std::any_of(scene.lights.begin(), scene.lights.end(), [](const Light& l) {
        return hasShadowMaps(l) && l.type == LightType::Directional;
    });
    return d.render(scene, camera, settings, cascaded ? d.measureDepthRange(depth, camera) : std::nullopt);
}

const ShadowMapSet& ShadowMaps::Impl::render(const Scene& scene, const Camera& camera, const ShadowMapSettings& settings,
                                             const std::optional<DistanceRange>& depthRange) {
    auto& d = *this;
    validateSettings(settings, d.ctx.info.maxTextureSize);
    analyzeProjection(camera);
    validateScene(scene);
    const std::vector<MapLayer> cameras = d.plan(scene, camera, settings, depthRange);
    d.set.camera = camera;
    d.set.resolution = settings.resolution;
    d.set.layers = static_cast<int>(cameras.size());
    d.set.depth = 0;
    d.set.flux = d.set.normal = d.set.position = 0;
    if (cameras.empty()) return d.set; // no shadowed light: no pass, no memory
    StateScope scope(d.ctx);
    PassScope pass(d.ctx, "shadow.maps");
    d.meshes.collectGarbage();
    d.ensureDepth(settings.resolution, static_cast<int>(cameras.size()));
    const bool reflective = std::any_of(cameras.begin(), cameras.end(), [](const MapLayer& m) { return m.reflective != nullptr; });
    if (reflective) d.ensureReflective();
    d.drawMaps(scene, cameras);
    d.set.depth = d.depth.get();
    d.set.flux = reflective ? d.flux.get() : 0;
    d.set.normal = reflective ? d.normal.get() : 0;
    d.set.position = reflective ? d.position.get() : 0;
    barrierForReaders(d.ctx);
    return d.set;
}

TextureView ShadowMaps::mask(const GBufferView& g, const ShadowMapSet& maps, std::size_t light,
                             const ShadowMaskSettings& settings) {
    auto& d = *impl_;
    auto& ctx = d.ctx;
    validateShadowMask(settings, "ShadowMaskSettings");
    const ShadowMapInfo* info = maps.find(light);
    if (!info)
        throw Error(ErrorCode::InvalidArgument, "ShadowMaps::mask: light " + std::to_string(light) +
                                                    " has no shadow map (only shadow-casting lights "
                                                    "have one)");
    if (maps.depth != d.depth.get() || maps.layers != d.depthLayers)
        throw Error(ErrorCode::InvalidArgument, "ShadowMaps::mask: the maps must be this module's latest render()");
    requireMapsFor(maps, g.camera, "ShadowMaps::mask");
    analyzeProjection(g.camera);
    const GBufferView view = checkScreenInputs(ctx, g, false, "ShadowMaps::mask");
    StateScope scope(ctx);
    d.frame.bind(ctx, view.camera, view.width, view.height, depthStepOf(ctx, view.depth.name), view.normalError);
    bindScreenInputs(ctx, view, false);
    d.binding.bind(ctx, d.depth.get(), {shadowRecord(*info, g.camera, settings, d.depthResolution)}, settings.filter);
    if (isMomentFilter(settings.filter)) d.prepareMoments(*info, settings);
    if (settings.filter == ShadowFilter::Pcss) { // the blocker search reads depths, not comparisons
        ctx.state.bindTexture(ctx, SHADOW_DEPTH_READ_UNIT, d.depth.get());
        ctx.state.bindSampler(ctx, SHADOW_DEPTH_READ_UNIT, ctx.nearestClampSampler());
    }
    // After the moments' own pass: passes are timed one after another, never nested.
    PassScope pass(ctx, "shadow.mask");
    const GLuint out = d.maskTexture.ensure(ctx, GL_R16F, view.width, view.height, "shadow.mask");
    ctx.gl.UseProgram(ctx.shaders->program({"shadows/shadow_mask.comp.glsl"}, shadowMaskDefines(settings)));
    ctx.state.bindImage(ctx, SHADOW_MASK_IMAGE, out, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_R16F);
    dispatchCompute2D(ctx, view.width, view.height, SHADOW_WORKGROUP);
    barrierForReaders(ctx);
    return {out, GL_R16F, view.width, view.height};
}

std::size_t ShadowMaps::memoryBytes() const {
    std::size_t total = 0;
    for (const auto& [pass, bytes] : memoryByPass()) total += bytes;
    return total;
}

std::vector<std::pair<std::string, std::size_t>> ShadowMaps::memoryByPass() const {
    const auto& d = *impl_;
    const std::size_t maps = d.depth ? 4u * std::size_t(d.depthResolution) * std::size_t(d.depthResolution) *
                                           std::size_t(d.depthLayers)
                                     : 0;
    const std::size_t momentBytes = d.momentsFormat == GL_RGBA32F ? 16u : 8u;
    const std::size_t moments = d.moments ? 2u * momentBytes * std::size_t(d.depthResolution) * std::size_t(d.depthResolution) *
                                                std::size_t(d.depthLayers)
                                          : 0;
    const std::size_t reflective = d.flux ? (8u + 8u + 16u) * std::size_t(d.depthResolution) * std::size_t(d.depthResolution) *
                                                std::size_t(d.depthLayers)
                                          : 0;
    return {{"shadow.maps", maps + reflective + d.meshes.memoryBytes()},
            {"shadow.moments", moments},
            {"shadow.mask", d.maskTexture.bytes() + d.frame.memoryBytes() + d.binding.memoryBytes()},
            {"shadow.depth_range", d.rangeBuffer ? 2 * sizeof(GLuint) : 0}};
}

} // namespace obscura
