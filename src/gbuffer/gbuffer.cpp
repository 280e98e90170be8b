#include "obscura/gbuffer.hpp"

#include "core/compute.hpp"
#include "core/context_impl.hpp"
#include "core/diagnostics.hpp"
#include "core/frame_uniforms.hpp"
#include "core/pass_scope.hpp"
#include "core/shader_library.hpp"
#include "core/texture_info.hpp"
#include "core/validate.hpp"
#include "gbuffer/host_inputs.hpp"
#include "gbuffer/host_region.hpp"
#include "gbuffer/light_records.hpp"
#include "shadows/shadow_lookup.hpp"
#include "core/mesh_cache.hpp"
#include "obscura/context.hpp"
#include "shaders/gbuffer/gbuffer_bindings.h"

#include <glm/gtc/type_ptr.hpp>

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <string>

namespace obscura {
namespace {

using namespace detail;



void dispatchOverImage(ContextImpl& ctx, int width, int height) {
    dispatchCompute2D(ctx, width, height, GBUFFER_WORKGROUP_SIZE);
    barrierForReaders(ctx);
}

} // namespace

struct GBuffer::Impl {
    explicit Impl(ContextImpl& c) : ctx(c), meshes(c) {}

    ContextImpl& ctx;
    MeshCache meshes;
    FrameUniforms frame;
    int width = 0, height = 0;
    Texture depth, normal, albedo, direct;
    Framebuffer fbo;
    Texture backDepth;     //!< second depth layer, only while depthLayers = 2 is asked for
    Framebuffer peelFbo;
    Sampler materialSampler;     //!< our uploaded images, mipmapped
    Sampler hostMaterialSampler; //!< host textures: no mipmaps assumed (an incomplete chain would sample black)
    SizedTexture adoptedNormal; //!< adopt() output
    Buffer nearPlaneCount;      //!< Diagnostic::DepthOnNearPlane's count, while diagnostics are delivered
    GLuint nearPlanePixels = 0; //!< its last value
    //! The depth texture, size and convention the near plane was last counted for.
    struct DepthKey {
        GLuint name = 0;
        int width = 0, height = 0;
        bool reversed = false;
        bool operator==(const DepthKey&) const = default;
    } nearPlaneChecked;
    bool clipDepthMismatchReported = false; //!< Diagnostic::ClipDepthMismatch was reported and still holds
    //! adopt()'s copies of HostGBuffer::region: depth, normal, albedo, radiance, back depth
    RegionCopy regionDepth, regionNormal, regionAlbedo, regionRadiance, regionBackDepth;
    SizedTexture positions;     //!< positions() output

    // Each given texture's `region`, copied into ours; the views name the copies after.
    void copyRegion(const HostRect& region, TextureView& hostDepth, TextureView& hostNormal, TextureView& hostAlbedo,
                    TextureView& hostRadiance, TextureView& hostBack) {
        PassScope pass(ctx, "gbuffer.region");
        const auto copyInto = [&](RegionCopy& copy, TextureView& view, GLenum format, const char* label) {
            if (!view) return copy.release();
            view = {copy.copy(ctx, view.name, format, region, label), format, region.width, region.height};
        };
        copyInto(regionDepth, hostDepth, hostDepth.internalFormat, "gbuffer.region_depth");
        copyInto(regionNormal, hostNormal, hostNormal.internalFormat, "gbuffer.region_normal");
        copyInto(regionAlbedo, hostAlbedo, hostAlbedo.internalFormat, "gbuffer.region_albedo");
        copyInto(regionRadiance, hostRadiance, hostRadiance.internalFormat, "gbuffer.region_radiance");
        copyInto(regionBackDepth, hostBack, hostBack.internalFormat, "gbuffer.region_back_depth");
    }

    void releaseRegionCopies() noexcept {
        for (RegionCopy* c : {&regionDepth, &regionNormal, &regionAlbedo, &regionRadiance, &regionBackDepth}) c->release();
    }

    // adopt()'s pass "gbuffer.normals": the host's normals (or, without them, the depth's) in
    // the view's contract, into adoptedNormal.
    // With `countNearPlane`, nearPlanePixels gets the pixels whose depth is the near plane's
    // (Diagnostic::DepthOnNearPlane; a read-back, which waits for the pass).
    TextureView convertNormals(const Camera& camera, const TextureView& depthIn, const TextureView& normalIn,
                               const HostNormals& normals, float deviation, int w, int h, bool countNearPlane) {
        PassScope pass(ctx, "gbuffer.normals");
        const GLuint converted = adoptedNormal.ensure(ctx, GL_RGBA16F, w, h, "gbuffer.normal");
        Defines defines = normals.defines; // as prepareAdopt
        if (countNearPlane) {
            defines.push_back("COUNT_NEAR_PLANE");
            if (!nearPlaneCount)
                nearPlaneCount = createBuffer(ctx, sizeof(GLuint), nullptr, GL_DYNAMIC_STORAGE_BIT, "gbuffer.near_plane_count");
            const GLuint zero = 0;
            ctx.gl.NamedBufferSubData(nearPlaneCount.get(), 0, sizeof zero, &zero);
            ctx.state.bindStorageBuffer(ctx, GBUFFER_NEAR_PLANE_SSBO, nearPlaneCount.get());
        }
        const GLuint program = ctx.shaders->program({"gbuffer/normals.comp.glsl"}, defines);
        ctx.gl.UseProgram(program);
        frame.bind(ctx, camera, w, h, depthStepOf(ctx, depthIn.name), normals.normalError);
        ctx.state.bindTexture(ctx, GBUFFER_DEPTH_TEXTURE_UNIT, depthIn.name);
        ctx.state.bindSampler(ctx, GBUFFER_DEPTH_TEXTURE_UNIT, ctx.nearestClampSampler());
        if (normalIn.name != 0) {
            ctx.state.bindTexture(ctx, GBUFFER_NORMAL_TEXTURE_UNIT, normalIn.name);
            ctx.state.bindSampler(ctx, GBUFFER_NORMAL_TEXTURE_UNIT, ctx.nearestClampSampler());
            ctx.gl.ProgramUniform1f(program, GBUFFER_LOC_NORMAL_DEVIATION,
                                    static_cast<float>(2.0 * std::sin(0.5 * double(deviation))));
        }
        ctx.state.bindImage(ctx, GBUFFER_OUTPUT_IMAGE_UNIT, converted, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA16F);
        dispatchOverImage(ctx, w, h);
        if (countNearPlane) ctx.gl.GetNamedBufferSubData(nearPlaneCount.get(), 0, sizeof nearPlanePixels, &nearPlanePixels);
        return {converted, GL_RGBA16F, w, h};
    }

    std::size_t regionCopyBytes() const noexcept {
        return regionDepth.bytes() + regionNormal.bytes() + regionAlbedo.bytes() + regionRadiance.bytes() +
               regionBackDepth.bytes();
    }

    void ensureTargets(int w, int h) {
        if (fbo && w == width && h == height) return;
        fbo.reset();
        peelFbo.reset();
        backDepth.reset();
        depth = createTexture2D(ctx, GL_DEPTH_COMPONENT32F, w, h, 1, "gbuffer.depth");
        normal = createTexture2D(ctx, GL_RGBA16F, w, h, 1, "gbuffer.normal");
        albedo = createTexture2D(ctx, GL_SRGB8_ALPHA8, w, h, 1, "gbuffer.albedo");
        direct = createTexture2D(ctx, GL_RGBA16F, w, h, 1, "gbuffer.direct");
        Framebuffer f = createFramebuffer(ctx, "gbuffer.render");
        auto& gl = ctx.gl;
        gl.NamedFramebufferTexture(f.get(), GL_DEPTH_ATTACHMENT, depth.get(), 0);
        gl.NamedFramebufferTexture(f.get(), GL_COLOR_ATTACHMENT0, normal.get(), 0);
        gl.NamedFramebufferTexture(f.get(), GL_COLOR_ATTACHMENT1, albedo.get(), 0);
        gl.NamedFramebufferTexture(f.get(), GL_COLOR_ATTACHMENT2, direct.get(), 0);
        const GLenum buffers[3] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1, GL_COLOR_ATTACHMENT2};
        gl.NamedFramebufferDrawBuffers(f.get(), 3, buffers);
        if (gl.CheckNamedFramebufferStatus(f.get(), GL_DRAW_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
            throw Error(ErrorCode::UnsupportedFeature, "the G-buffer framebuffer (32F depth, RGBA16F, SRGB8_ALPHA8, "
                                                       "RGBA16F) is not complete on this driver");
        fbo = std::move(f);
        width = w;
        height = h;
    }

    void ensurePeelTarget() {
        if (peelFbo) return;
        backDepth = createTexture2D(ctx, GL_DEPTH_COMPONENT32F, width, height, 1, "gbuffer.back_depth");
        Framebuffer f = createFramebuffer(ctx, "gbuffer.peel");
        ctx.gl.NamedFramebufferTexture(f.get(), GL_DEPTH_ATTACHMENT, backDepth.get(), 0);
        ctx.gl.NamedFramebufferDrawBuffer(f.get(), GL_NONE);
        if (ctx.gl.CheckNamedFramebufferStatus(f.get(), GL_DRAW_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
            throw Error(ErrorCode::UnsupportedFeature, "the depth-peeling framebuffer (32F depth only) is not complete");
        peelFbo = std::move(f);
    }

    LightRecords lights;

    GLuint materialTexture(const Material& m) {
        if (m.albedoTexture != 0) return m.albedoTexture;
        if (m.albedoImage) return meshes.albedoTexture(m.albedoImage);
        return 0;
    }

    // What the fragment shader lights with: its permutation and light count.
    struct Lighting {
        bool direct = false;
        bool rects = false; // any rect light: the polygon clipping is compiled in only then
        int count = 0;
        bool shadows = false; // some light has maps: the lookups are compiled in only then
        ShadowFilter filter = ShadowFilter::Hard;
    };

    void draw(const DrawableMesh& mesh, const glm::mat4& model, const Material& material, const glm::dmat4& view,
              const Lighting& lighting, bool peel = false) {
        auto& gl = ctx.gl;
        // The peeling pass writes depth only: no texture, no lighting (PEEL implies it).
        const GLuint texture = mesh.hasTexcoords && !peel ? materialTexture(material) : 0;
        Defines defines;
        if (mesh.hasNormals) defines.push_back("HAS_NORMALS");
        if (mesh.hasTexcoords) defines.push_back("HAS_TEXCOORDS");
        if (texture) defines.push_back("ALBEDO_TEXTURE");
        if (peel) defines.push_back("PEEL");
        else if (!lighting.direct) defines.push_back("NO_DIRECT_LIGHTING");
        else {
            if (lighting.rects) defines.push_back("RECT_LIGHTS");
            if (lighting.shadows) defines.insert(defines.end(), {"SHADOWS", shadowFilterDefine(lighting.filter)});
        }
        const GLuint program = ctx.shaders->program(
            {"gbuffer/gbuffer.vert.glsl", "gbuffer/gbuffer.geom.glsl", "gbuffer/gbuffer.frag.glsl"}, defines);
        gl.UseProgram(program);
        // Model-view in double: a scene far from the origin keeps its precision near the camera.
        const glm::dmat4 modelView = view * glm::dmat4(model);
        const glm::mat4 mv(modelView);
        const glm::mat4 normalMatrix(glm::transpose(glm::inverse(glm::dmat3(modelView))));
        gl.ProgramUniformMatrix4fv(program, GBUFFER_LOC_MODEL_VIEW, 1, GL_FALSE, glm::value_ptr(mv));
        gl.ProgramUniformMatrix4fv(program, GBUFFER_LOC_NORMAL_MATRIX, 1, GL_FALSE, glm::value_ptr(normalMatrix));
        gl.ProgramUniform3fv(program, GBUFFER_LOC_ALBEDO, 1, glm::value_ptr(material.albedo));
        gl.ProgramUniform3fv(program, GBUFFER_LOC_EMISSION, 1, glm::value_ptr(material.emission));
        gl.ProgramUniform1i(program, GBUFFER_LOC_LIGHT_COUNT, lighting.count);
        if (texture) {
            ctx.state.bindTexture(ctx, GBUFFER_ALBEDO_TEXTURE_UNIT, texture);
            ctx.state.bindSampler(ctx, GBUFFER_ALBEDO_TEXTURE_UNIT, materialSamplerFor(material));
        }
        drawMesh(ctx, mesh);
    }

    GLuint materialSamplerFor(const Material& m) {
        if (m.albedoTexture != 0) {
            if (!hostMaterialSampler)
                hostMaterialSampler = createSampler(ctx, GL_LINEAR, GL_REPEAT, "gbuffer.host_material_sampler");
            return hostMaterialSampler.get();
        }
        if (!materialSampler)
            materialSampler = createSampler(ctx, GL_LINEAR_MIPMAP_LINEAR, GL_REPEAT, "gbuffer.material_sampler");
        return materialSampler.get();
    }

    void validateHostTexture(GLuint name, const std::string& who) {
        requireReadableAs(ctx, name, queryTexture2D(ctx, name, who), who, SampledAs::Colour);
    }
};

GBuffer::GBuffer(Context& context) : impl_(std::make_unique<Impl>(context.impl())) {}
GBuffer::~GBuffer() = default;

GBufferView GBuffer::render(const Scene& scene, const Camera& camera, const GBufferSettings& settings) {
    auto& ctx = impl_->ctx;
    requireImageSize(settings.width, settings.height, ctx.info.maxTextureSize, "GBufferSettings");
    validateSettings(GBufferSettings::table(), settings, "GBufferSettings");
    const ProjectionInfo projection = analyzeProjection(camera);
    validateScene(scene);
    if (settings.shadows)
        validateLightShadows(*settings.shadows, settings.shadowFilter, scene.lights.size(), camera, "GBufferSettings");
    for (std::size_t i = 0; i < scene.materials.size(); ++i) {
        const GLuint texture = scene.materials[i].albedoTexture;
        if (texture == 0) continue;
        const std::string who = "Scene::materials[" + std::to_string(i) + "].albedoTexture";
        impl_->validateHostTexture(texture, who);
        // Last frame's image on an in-scene screen, say: drawn into while sampled.
        requireNotOwnOutput({{who.c_str(), texture}},
                            {impl_->depth.get(), impl_->normal.get(), impl_->albedo.get(), impl_->direct.get(),
                             impl_->backDepth.get()},
                            "GBuffer");
    }

    StateScope scope(ctx);
    PassScope pass(ctx, "gbuffer.render");
    auto& gl = ctx.gl;
    impl_->meshes.collectGarbage();
    // Host meshes first: reading a host VAO's layout binds it.
    std::vector<DrawableMesh> hostMeshes;
    for (std::size_t i = 0; i < scene.meshRefs.size(); ++i) hostMeshes.push_back(impl_->meshes.hostMesh(i, scene.meshRefs[i]));
    impl_->ensureTargets(settings.width, settings.height);
    const glm::dmat4 view(camera.view);
    impl_->frame.bind(ctx, camera, settings.width, settings.height, 0.0); // our depth is 32-bit float
    const bool shadowed = impl_->lights.bindShadows(ctx, scene.lights, camera,
                                                    settings.directLighting ? settings.shadows : nullptr, settings.shadowFilter);
    impl_->lights.upload(ctx, scene.lights, view, "gbuffer.lights");

    const GLuint fbo = impl_->fbo.get();
    gl.BindFramebuffer(GL_FRAMEBUFFER, fbo);
    setViewport(ctx, 0, 0, settings.width, settings.height);
    const bool zeroToOne = camera.clipDepth == ClipDepth::ZeroToOne;
    applyDrawState(ctx, {true, true, static_cast<GLenum>(projection.reversedZ ? GL_GREATER : GL_LESS), false, true,
                         static_cast<GLenum>(zeroToOne ? GL_ZERO_TO_ONE : GL_NEGATIVE_ONE_TO_ONE), false});
    const float zero[4] = {0, 0, 0, 0};
    const float background[4] = {settings.background.r, settings.background.g, settings.background.b, 0.0f};
    gl.ClearNamedFramebufferfv(fbo, GL_DEPTH, 0, &projection.clearDepth);
    gl.ClearNamedFramebufferfv(fbo, GL_COLOR, 0, zero);
    gl.ClearNamedFramebufferfv(fbo, GL_COLOR, 1, zero);
    gl.ClearNamedFramebufferfv(fbo, GL_COLOR, 2, background);

    const Impl::Lighting lighting{settings.directLighting,
                                  std::any_of(scene.lights.begin(), scene.lights.end(),
                                              [](const Light& l) { return l.type == LightType::Rect; }),
                                  static_cast<int>(scene.lights.size()), shadowed, settings.shadowFilter.filter};
    const auto drawScene = [&](bool peel) {
        for (const Mesh& mesh : scene.meshes) {
            const DrawableMesh d = impl_->meshes.cpuMesh(mesh.data);
            if (d.count > 0) impl_->draw(d, mesh.model, scene.materials[mesh.material], view, lighting, peel);
        }
        for (std::size_t i = 0; i < scene.meshRefs.size(); ++i)
            impl_->draw(hostMeshes[i], scene.meshRefs[i].model, scene.materials[scene.meshRefs[i].material], view,
                        lighting, peel);
    };
    drawScene(false);
    if (settings.depthLayers == 2) {
        impl_->ensurePeelTarget();
        gl.BindFramebuffer(GL_FRAMEBUFFER, impl_->peelFbo.get());
        gl.ClearNamedFramebufferfv(impl_->peelFbo.get(), GL_DEPTH, 0, &projection.clearDepth);
        ctx.state.bindTexture(ctx, GBUFFER_DEPTH_TEXTURE_UNIT, impl_->depth.get());
        ctx.state.bindSampler(ctx, GBUFFER_DEPTH_TEXTURE_UNIT, ctx.nearestClampSampler());
        drawScene(true);
    } else {
        impl_->peelFbo.reset(); // not asked for: not kept
        impl_->backDepth.reset();
    }

    GBufferView v;
    v.depth = {impl_->depth.get(), GL_DEPTH_COMPONENT32F, settings.width, settings.height};
    v.normal = {impl_->normal.get(), GL_RGBA16F, settings.width, settings.height};
    v.albedo = {impl_->albedo.get(), GL_SRGB8_ALPHA8, settings.width, settings.height};
    v.directRadiance = {impl_->direct.get(), GL_RGBA16F, settings.width, settings.height};
    if (settings.depthLayers == 2) v.backDepth = {impl_->backDepth.get(), GL_DEPTH_COMPONENT32F, settings.width, settings.height};
    v.camera = camera;
    v.width = settings.width;
    v.height = settings.height;
    return v;
}

float adoptedNormalError(NormalEncoding encoding, int bits) {
    if (bits < 1 || bits > 32) throw Error(ErrorCode::InvalidArgument, "adoptedNormalError: bits must be in [1, 32]");
    const double delta = encoding == NormalEncoding::Unsigned ? std::sqrt(3.0) / (std::ldexp(1.0, bits) - 1.0)
                         : bits <= 16                         ? std::ldexp(1.0, -10)
                                                              : std::ldexp(1.0, -23);
    return static_cast<float>(std::asin(std::min(delta, 1.0)) + kHalfNormalError);
}

GBufferView GBuffer::adopt(const HostGBuffer& host, const Camera& camera) {
    auto& ctx = impl_->ctx;
    analyzeProjection(camera);
    const TextureInfo depth = queryTexture2D(ctx, host.depth.name, "HostGBuffer::depth");
    requireDescribedAs(host.depth, depth, "HostGBuffer::depth");
    requireSampledDepth(ctx, host.depth.name, depth, "HostGBuffer::depth");
    requireImageSize(depth.width, depth.height, ctx.info.maxTextureSize, "HostGBuffer::depth");
    requireBaseLevelZero(ctx, host.depth.name, "HostGBuffer::depth");
    const HostNormals normals = checkHostNormals(ctx, host, depth);
    TextureView normalIn = normals.texture;
    TextureView albedo = hostColour(ctx, host.albedo, "HostGBuffer::albedo", depth, SampledAs::Rgb);
    TextureView directRadiance = hostColour(ctx, host.directRadiance, "HostGBuffer::directRadiance", depth, SampledAs::FloatRgb);
    TextureView backDepth = hostBackDepth(ctx, host.backDepth, host.depth.name, depth);
    // A view adopt() returned, handed back: its normals or region copies would be read while
    // overwritten, reallocated or freed.
    const Impl& own = *impl_;
    requireNotOwnOutput({{"HostGBuffer::depth", host.depth.name},
                         {"HostGBuffer::normal", host.normal.name},
                         {"HostGBuffer::albedo", host.albedo.name},
                         {"HostGBuffer::directRadiance", host.directRadiance.name},
                         {"HostGBuffer::backDepth", host.backDepth.name}},
                        {own.adoptedNormal.get(), own.regionDepth.name(), own.regionNormal.name(), own.regionAlbedo.name(),
                         own.regionRadiance.name(), own.regionBackDepth.name()},
                        "GBuffer");
    const HostRect region = resolveRegion(host.region, depth);
    if (!coversWhole(region, depth)) {
        requireCopyable(ctx, host.depth.name, depth.internalFormat, "HostGBuffer::depth");
        if (normalIn) requireCopyable(ctx, normalIn.name, normalIn.internalFormat, "HostGBuffer::normal");
        if (albedo) requireCopyable(ctx, albedo.name, albedo.internalFormat, "HostGBuffer::albedo");
        if (directRadiance) requireCopyable(ctx, directRadiance.name, directRadiance.internalFormat, "HostGBuffer::directRadiance");
        if (backDepth) requireCopyable(ctx, backDepth.name, backDepth.internalFormat, "HostGBuffer::backDepth");
    }

    reportClipDepthMismatch(ctx, camera, impl_->clipDepthMismatchReported);
    // Counted once per depth texture, size and convention: the count is a read-back, which
    // stalls. Queried before the scope, which may turn the host's GL_DEBUG_OUTPUT on or off.
    const Impl::DepthKey depthKey{host.depth.name, depth.width, depth.height, analyzeProjection(camera).reversedZ};
    const bool countNearPlane = !normals.inPlace && !(depthKey == impl_->nearPlaneChecked) && diagnosticsDelivered(ctx);
    if (countNearPlane) impl_->nearPlaneChecked = depthKey;
    StateScope scope(ctx);
    TextureView depthIn{host.depth.name, depth.internalFormat, depth.width, depth.height};
    if (coversWhole(region, depth)) impl_->releaseRegionCopies();
    else impl_->copyRegion(region, depthIn, normalIn, albedo, directRadiance, backDepth);
    const int w = region.width, h = region.height;
    TextureView normal = normalIn;
    if (normals.inPlace) impl_->adoptedNormal.release();
    else normal = impl_->convertNormals(camera, depthIn, normalIn, normals, host.normalDeviation, w, h, countNearPlane);
    if (countNearPlane) reportNearPlanePixels(ctx, impl_->nearPlanePixels, w, h, camera);

    GBufferView v;
    v.depth = {depthIn.name, depth.internalFormat, w, h};
    v.normal = normal;
    v.normalError = normals.normalError;
    v.albedo = albedo;
    v.directRadiance = directRadiance;
    v.backDepth = backDepth;
    v.camera = camera;
    v.width = w;
    v.height = h;
    return v;
}

void GBuffer::prepareAdopt(const HostGBuffer& host) {
    requireNormalEnumerators(host);
    if (host.normal.name != 0 && host.normalEncoding == NormalEncoding::ViewContract) return; // no pass
    auto& ctx = impl_->ctx;
    const bool counting = diagnosticsDelivered(ctx); // the first adopt() counts (Diagnostic::DepthOnNearPlane)
    StateScope scope(ctx);
    Defines defines = normalDefines(host);
    ctx.shaders->program({"gbuffer/normals.comp.glsl"}, defines);
    if (!counting) return;
    defines.push_back("COUNT_NEAR_PLANE");
    ctx.shaders->program({"gbuffer/normals.comp.glsl"}, defines);
}

TextureView GBuffer::positions(const GBufferView& view) {
    auto& ctx = impl_->ctx;
    analyzeProjection(view.camera);
    const TextureInfo depth = queryTexture2D(ctx, view.depth.name, "GBufferView::depth");
    requireReadableAs(ctx, view.depth.name, depth, "GBufferView::depth", SampledAs::Depth);
    StateScope scope(ctx);
    PassScope pass(ctx, "gbuffer.positions");
    const int w = depth.width, h = depth.height;
    const GLuint positions = impl_->positions.ensure(ctx, GL_RGBA32F, w, h, "gbuffer.positions");
    ctx.gl.UseProgram(ctx.shaders->program({"gbuffer/positions.comp.glsl"}));
    impl_->frame.bind(ctx, view.camera, w, h, depthStepOf(ctx, view.depth.name));
    ctx.state.bindTexture(ctx, GBUFFER_DEPTH_TEXTURE_UNIT, view.depth.name);
    ctx.state.bindSampler(ctx, GBUFFER_DEPTH_TEXTURE_UNIT, ctx.nearestClampSampler());
    ctx.state.bindImage(ctx, GBUFFER_OUTPUT_IMAGE_UNIT, positions, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
    dispatchOverImage(ctx, w, h);
    return {positions, GL_RGBA32F, w, h};
}

std::size_t GBuffer::memoryBytes() const {
    const auto& i = *impl_;
    std::size_t total = i.meshes.memoryBytes() + i.frame.memoryBytes();
    if (i.fbo)
        total += static_cast<std::size_t>(i.width) * static_cast<std::size_t>(i.height) *
                 (bytesPerTexel(GL_DEPTH_COMPONENT32F) + 2 * bytesPerTexel(GL_RGBA16F) + bytesPerTexel(GL_SRGB8_ALPHA8));
    if (i.backDepth) total += static_cast<std::size_t>(i.width) * static_cast<std::size_t>(i.height) * bytesPerTexel(GL_DEPTH_COMPONENT32F);
    total += i.lights.memoryBytes();
    total += i.adoptedNormal.bytes() + i.positions.bytes() + i.regionCopyBytes() +
             (i.nearPlaneCount ? sizeof(GLuint) : 0);
    return total;
}

} // namespace obscura
