// Host contract: every public entry point leaves the host's GL state exactly as it found it
// (StatePolicy::Preserve), or at the documented initial values (StatePolicy::Clobber), and
// works correctly whatever state the host left behind.
#include "gl_fixture.hpp"
#include "gl_state.hpp"
#include "host_extension_state.hpp"
#include "obscura/obscura.hpp"
#include "scene_builders.hpp"

#include <catch2/catch.hpp>

#include <cstdio>
#include <functional>
#include <string>

using namespace obscura;

namespace {

// Host objects bound while Obscura runs.
struct HostObjects {
    GLuint program = 0, vao = 0, fbo[2]{}, renderbuffer = 0, textures[48]{}, samplers[16]{}, buffers[8]{},
           feedback = 0, pipeline = 0, timeQuery = 0;

    HostObjects() {
        const char* vs = "#version 450 core\nvoid main() { gl_Position = vec4(0); }\n";
        const char* fs = "#version 450 core\nout vec4 c; void main() { c = vec4(1); }\n";
        program = glCreateProgram();
        for (auto [type, src] : {std::pair{GL_VERTEX_SHADER, vs}, std::pair{GL_FRAGMENT_SHADER, fs}}) {
            const GLuint s = glCreateShader(type);
            glShaderSource(s, 1, &src, nullptr);
            glCompileShader(s);
            glAttachShader(program, s);
            glDeleteShader(s);
        }
        glLinkProgram(program);
        glCreateVertexArrays(1, &vao);
        glCreateFramebuffers(2, fbo);
        glCreateRenderbuffers(1, &renderbuffer);
        glCreateTextures(GL_TEXTURE_2D, 16, textures);
        glCreateTextures(GL_TEXTURE_3D, 16, textures + 16);
        glCreateTextures(GL_TEXTURE_CUBE_MAP, 16, textures + 32);
        for (int i = 0; i < 16; ++i) {
            glTextureStorage2D(textures[i], 1, GL_RGBA8, 4, 4);
            glTextureStorage3D(textures[16 + i], 1, GL_RGBA8, 2, 2, 2);
            glTextureStorage2D(textures[32 + i], 1, GL_RGBA8, 4, 4);
        }
        glCreateSamplers(16, samplers);
        glCreateBuffers(8, buffers);
        for (GLuint b : buffers) glNamedBufferData(b, 4096, nullptr, GL_DYNAMIC_DRAW);
        glCreateTransformFeedbacks(1, &feedback);
        glCreateProgramPipelines(1, &pipeline);
        glCreateQueries(GL_TIME_ELAPSED, 1, &timeQuery);
    }
    ~HostObjects() {
        glDeleteProgram(program);
        glDeleteVertexArrays(1, &vao);
        glDeleteFramebuffers(2, fbo);
        glDeleteRenderbuffers(1, &renderbuffer);
        glDeleteTextures(48, textures);
        glDeleteSamplers(16, samplers);
        glDeleteBuffers(8, buffers);
        glDeleteTransformFeedbacks(1, &feedback);
        glDeleteProgramPipelines(1, &pipeline);
        glDeleteQueries(1, &timeQuery);
    }
};

constexpr GLenum kMultiplyKhr = 0x9294; // GL_MULTIPLY_KHR, which the headers the tests include lack

bool hasGlExtension(const char* name) {
    GLint count = 0;
    glGetIntegerv(GL_NUM_EXTENSIONS, &count);
    for (GLint i = 0; i < count; ++i)
        if (std::string(reinterpret_cast<const char*>(glGetStringi(GL_EXTENSIONS, GLuint(i)))) == name) return true;
    return false;
}

// Every item on Obscura's list (and a lot that is not) set to a non-default value.
void setUnusualState(const HostObjects& h) {
    glUseProgram(h.program);
    glBindProgramPipeline(h.pipeline);
    glBindVertexArray(h.vao);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, h.fbo[0]);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, h.fbo[1]);
    glBindRenderbuffer(GL_RENDERBUFFER, h.renderbuffer);
    glBindTransformFeedback(GL_TRANSFORM_FEEDBACK, h.feedback);
    glViewportIndexedf(0, 3, 5, 17, 19);
    glViewportIndexedf(1, 1, 2, 3, 4);
    glScissorIndexed(0, 1, 2, 30, 40);
    glScissorIndexed(1, 5, 6, 7, 8);
    glDepthRangeIndexed(0, 0.2, 0.8);
    glDepthRangeIndexed(1, 0.1, 0.3);
    glEnablei(GL_SCISSOR_TEST, 0);
    glEnablei(GL_SCISSOR_TEST, 2);
    for (GLenum cap : {GL_DEPTH_TEST, GL_STENCIL_TEST, GL_CULL_FACE, GL_COLOR_LOGIC_OP, GL_PRIMITIVE_RESTART,
                       GL_PRIMITIVE_RESTART_FIXED_INDEX, GL_DEPTH_CLAMP, GL_FRAMEBUFFER_SRGB, GL_POLYGON_OFFSET_FILL,
                       GL_POLYGON_OFFSET_LINE, GL_POLYGON_OFFSET_POINT, GL_RASTERIZER_DISCARD, GL_SAMPLE_ALPHA_TO_COVERAGE,
                       GL_SAMPLE_COVERAGE, GL_SAMPLE_MASK, GL_PROGRAM_POINT_SIZE, GL_LINE_SMOOTH, GL_SAMPLE_SHADING,
                       GL_POLYGON_SMOOTH,
                       GL_CLIP_DISTANCE0, GL_CLIP_DISTANCE3, GL_CLIP_DISTANCE7})
        glEnable(cap);
    glDisable(GL_DITHER);
    glDisable(GL_MULTISAMPLE);
    glDisable(GL_TEXTURE_CUBE_MAP_SEAMLESS);
    glEnablei(GL_BLEND, 0);
    glEnablei(GL_BLEND, 3);
    glBlendFuncSeparatei(0, GL_SRC_COLOR, GL_DST_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_CONSTANT_COLOR);
    glBlendFuncSeparatei(2, GL_DST_COLOR, GL_SRC_ALPHA, GL_ZERO, GL_ONE);
    glBlendEquationSeparatei(0, GL_FUNC_SUBTRACT, GL_MAX);
    glBlendEquationSeparatei(2, GL_MIN, GL_FUNC_REVERSE_SUBTRACT);
    // An advanced equation (KHR_blend_equation_advanced; llvmpipe has it) can only be set for
    // RGB and alpha together: glBlendEquationSeparatei refuses it (GL_INVALID_ENUM).
    if (hasGlExtension("GL_KHR_blend_equation_advanced")) glBlendEquationi(1, kMultiplyKhr);
    test::setUnusualExtensionState();
    glBlendColor(0.1f, 0.2f, 0.3f, 0.4f);
    glColorMaski(0, GL_FALSE, GL_TRUE, GL_FALSE, GL_TRUE);
    glColorMaski(1, GL_TRUE, GL_FALSE, GL_TRUE, GL_FALSE);
    glColorMaski(7, GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
    glDepthMask(GL_FALSE);
    glStencilMaskSeparate(GL_FRONT, 0x0F);
    glStencilMaskSeparate(GL_BACK, 0xF0);
    glStencilFuncSeparate(GL_FRONT, GL_LEQUAL, 3, 0x7);
    glStencilFuncSeparate(GL_BACK, GL_NOTEQUAL, 5, 0x3);
    glStencilOpSeparate(GL_FRONT, GL_INCR, GL_DECR_WRAP, GL_INVERT);
    glStencilOpSeparate(GL_BACK, GL_ZERO, GL_REPLACE, GL_INCR_WRAP);
    glDepthFunc(GL_GREATER);
    glLogicOp(GL_XOR);
    glClipControl(GL_UPPER_LEFT, GL_ZERO_TO_ONE);
    glPolygonMode(GL_FRONT_AND_BACK, GL_LINE);
    glPolygonOffset(1.5f, 2.5f);
    glFrontFace(GL_CW);
    glCullFace(GL_FRONT);
    glClampColor(GL_CLAMP_READ_COLOR, GL_TRUE);
    glPushDebugGroup(GL_DEBUG_SOURCE_APPLICATION, 7, -1, "host group");
    glClearColor(0.3f, 0.6f, 0.9f, 0.5f);
    glClearDepth(0.25);
    glClearStencil(9);
    glPointSize(3.0f);
    glPrimitiveRestartIndex(77);
    glProvokingVertex(GL_FIRST_VERTEX_CONVENTION);
    glPatchParameteri(GL_PATCH_VERTICES, 4);
    glHint(GL_FRAGMENT_SHADER_DERIVATIVE_HINT, GL_NICEST);
    for (GLuint unit = 0; unit < 16; ++unit) {
        glActiveTexture(GL_TEXTURE0 + unit);
        glBindTexture(GL_TEXTURE_2D, h.textures[unit]);
        glBindTexture(GL_TEXTURE_3D, h.textures[16 + unit]);
        glBindTexture(GL_TEXTURE_CUBE_MAP, h.textures[32 + unit]);
        glBindSampler(unit, h.samplers[unit]);
    }
    glActiveTexture(GL_TEXTURE7);
    for (GLuint i = 0; i < 4; ++i) glBindImageTexture(i, h.textures[i], 0, GL_FALSE, 0, GL_READ_WRITE, GL_RGBA8);
    for (GLuint i = 0; i < 9; ++i) glBindBufferRange(GL_UNIFORM_BUFFER, i, h.buffers[i % 8], 256 * (i % 4), 512);
    for (GLuint i = 0; i < 5; ++i) glBindBufferRange(GL_SHADER_STORAGE_BUFFER, i, h.buffers[(i + 3) % 8], 256, 1024);
    glBindBufferBase(GL_ATOMIC_COUNTER_BUFFER, 1, h.buffers[6]);
    const GLenum targets[] = {GL_ARRAY_BUFFER, GL_COPY_READ_BUFFER, GL_COPY_WRITE_BUFFER, GL_PIXEL_PACK_BUFFER,
                              GL_PIXEL_UNPACK_BUFFER, GL_DRAW_INDIRECT_BUFFER, GL_DISPATCH_INDIRECT_BUFFER,
                              GL_QUERY_BUFFER, GL_TEXTURE_BUFFER, GL_UNIFORM_BUFFER, GL_SHADER_STORAGE_BUFFER,
                              GL_ATOMIC_COUNTER_BUFFER, GL_TRANSFORM_FEEDBACK_BUFFER};
    for (std::size_t i = 0; i < std::size(targets); ++i) glBindBuffer(targets[i], h.buffers[i % 8]);
    glPixelStorei(GL_PACK_ALIGNMENT, 2);
    glPixelStorei(GL_PACK_ROW_LENGTH, 3);
    glPixelStorei(GL_PACK_IMAGE_HEIGHT, 5);
    glPixelStorei(GL_PACK_SKIP_PIXELS, 1);
    glPixelStorei(GL_PACK_SKIP_ROWS, 2);
    glPixelStorei(GL_PACK_SKIP_IMAGES, 3);
    glPixelStorei(GL_PACK_SWAP_BYTES, GL_TRUE);
    glPixelStorei(GL_PACK_LSB_FIRST, GL_TRUE);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 8);
    glPixelStorei(GL_UNPACK_ROW_LENGTH, 7);
    glPixelStorei(GL_UNPACK_IMAGE_HEIGHT, 6);
    glPixelStorei(GL_UNPACK_SKIP_PIXELS, 4);
    glPixelStorei(GL_UNPACK_SKIP_ROWS, 3);
    glPixelStorei(GL_UNPACK_SKIP_IMAGES, 2);
    glPixelStorei(GL_UNPACK_SWAP_BYTES, GL_TRUE);
    glPixelStorei(GL_UNPACK_LSB_FIRST, GL_TRUE);
}

// The scene exercises every draw path: CPU meshes with and without texcoords and a CPU
// albedo image, a host mesh read from a host VAO, and every light type.
struct StateScene {
    Scene scene;
    GLuint vertexBuffer = 0, hostVao = 0, hostColor = 0, hostFramebuffer = 0;
    Camera camera = Camera::perspective({{0.3f, 1.5f, 3}, {0, 0, 0}, {0, 1, 0}}, 1.0f, 1.25f, 0.1f, 20.0f,
                                        DepthMode::Reversed);

    StateScene() {
        scene = test::quadScene({{{{{-2, 0, -2}, {-2, 0, 2}, {2, 0, 2}, {2, 0, -2}}}}});
        auto textured = std::make_shared<MeshData>(*test::quadMesh({{{-1, 0, -1}, {1, 0, -1}, {1, 1, -1}, {-1, 1, -1}}}));
        textured->texcoords = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
        auto image = std::make_shared<TextureImage>();
        image->width = image->height = 2;
        image->rgba = {255, 0, 0, 255, 0, 255, 0, 255, 0, 0, 255, 255, 255, 255, 255, 255};
        Material m;
        m.albedoImage = image;
        scene.materials.push_back(m);
        scene.meshes.push_back({textured, glm::mat4(1), 1, "textured"});
        const float tri[9] = {0.5f, 0.1f, 0.5f, 1.5f, 0.1f, 0.5f, 1.0f, 0.8f, 0.5f};
        glCreateBuffers(1, &vertexBuffer);
        glNamedBufferData(vertexBuffer, sizeof tri, tri, GL_STATIC_DRAW);
        glCreateVertexArrays(1, &hostVao);
        glVertexArrayVertexBuffer(hostVao, 0, vertexBuffer, 0, 12);
        glVertexArrayAttribFormat(hostVao, 2, 3, GL_FLOAT, GL_FALSE, 0);
        glVertexArrayAttribBinding(hostVao, 2, 0);
        glEnableVertexArrayAttrib(hostVao, 2);
        // A framebuffer of the host's for output passes (surfaceless EGL has no default one).
        glCreateTextures(GL_TEXTURE_2D, 1, &hostColor);
        glTextureStorage2D(hostColor, 1, GL_RGBA8, 8, 8);
        glCreateFramebuffers(1, &hostFramebuffer);
        glNamedFramebufferTexture(hostFramebuffer, GL_COLOR_ATTACHMENT0, hostColor, 0);
        MeshRef ref;
        ref.vao = hostVao;
        ref.positionLocation = 2;
        ref.count = 3;
        scene.meshRefs.push_back(ref);
        for (LightType type : {LightType::Point, LightType::Spot, LightType::Directional}) {
            Light l;
            l.type = type;
            l.position = {0.5f, 2, 0.5f};
            scene.lights.push_back(l);
        }
    }
    ~StateScene() {
        glDeleteFramebuffers(1, &hostFramebuffer);
        glDeleteTextures(1, &hostColor);
        glDeleteBuffers(1, &vertexBuffer);
        glDeleteVertexArrays(1, &hostVao);
    }
};

// Runs each public entry point once, reporting it by name to `check`.
void forEachEntryPoint(test::GlFixture& gl, StatePolicy policy, const StateScene& s,
                       const std::function<void(const std::string&, const std::function<void()>&)>& check,
                       DebugCallback debugOutput = {}) {
    std::unique_ptr<Context> ctx;
    ContextDesc desc = gl.desc(policy);
    desc.debugOutput = std::move(debugOutput);
    check("Context::Context", [&] { ctx = std::make_unique<Context>(desc); });
    auto gbuffer = std::make_unique<GBuffer>(*ctx);
    GBufferView view;
    check("GBuffer::render", [&] { view = gbuffer->render(s.scene, s.camera, {40, 32, true, {}}); });
    check("GBuffer::render (again, cached)", [&] { view = gbuffer->render(s.scene, s.camera, {40, 32, true, {}}); });
    TextureView positions;
    check("GBuffer::positions", [&] { positions = gbuffer->positions(view); });
    // Adopts the view's depth with the buffers asked for (any RGBA16F texture of the right
    // size stands in for normals) over `region` (empty: the whole texture).
    const auto adopt = [&](bool normals, bool colours, HostRect region) {
        HostGBuffer host;
        host.depth = view.depth;
        if (normals) host.normal = view.directRadiance;
        if (colours) host.albedo = view.albedo, host.directRadiance = view.directRadiance;
        host.region = region;
        gbuffer->adopt(host, s.camera);
    };
    check("GBuffer::adopt (depth only)", [&] { adopt(false, false, {}); });
    check("GBuffer::adopt (with normals)", [&] { adopt(true, false, {}); });
    check("GBuffer::adopt (with albedo and lit image)", [&] { adopt(false, true, {}); });
    check("GBuffer::adopt (a region of every buffer)", [&] { adopt(true, true, {3, 2, 30, 25}); });
    check("readTexture", [&] { readTexture(*ctx, positions); });
    check("Profiler::latest", [&] { ctx->profiler().latest(); });
    check("Profiler::statistics (GPU clock, waiting)", [&] {
        ctx->profiler().setClock(ClockSource::GpuTimestamp);
        gbuffer->render(s.scene, s.camera, {40, 32, true, {}});
        ctx->profiler().statistics(true);
    });
    check("GBuffer::render throwing on a bad host VAO", [&] {
        Scene bad = s.scene;
        bad.meshRefs[0].positionLocation = 9; // not enabled in the host VAO
        CHECK_THROWS_AS(gbuffer->render(bad, s.camera, {40, 32, true, {}}), Error);
    });
    auto voxelizer = std::make_unique<Voxelizer>(*ctx);
    VoxelizerSettings vs;
    vs.resolution = 16;
    check("Voxelizer::voxelize (surface, host VAO)", [&] { voxelizer->voxelize(s.scene, vs); });
    check("Voxelizer::voxelize (solid, 2 targets)", [&] {
        VoxelizerSettings solid = vs;
        solid.mode = VoxelMode::Solid;
        solid.targets = 2;
        voxelizer->voxelize(s.scene, solid);
    });
    check("Voxelizer::trace", [&] {
        voxelizer->trace({{glm::vec3(0.0f), glm::vec3(16.0f, 16.0f, 256.0f)}}, {});
    });
    check("Voxelizer::download", [&] { voxelizer->download(); });
    check("Voxelizer::downloadQuadtree", [&] { voxelizer->downloadQuadtree(1); });
    auto ao = std::make_unique<AmbientOcclusion>(*ctx);
    AmbientOcclusionView aoView;
    check("AmbientOcclusion::run (half resolution, blur)", [&] {
        aoView = ao->run(view, {.rays = 4, .resolution = AoResolution::Half, .blurRadius = 1, .bentNormals = true});
    });
    check("AmbientOcclusion::prepare", [&] {
        ao->prepare({.method = AoMethod::Horizon, .resolution = AoResolution::Quarter, .temporal = {.enabled = true}});
    });
    check("AmbientOcclusion::run (temporal, twice: the history reprojected)", [&] {
        AmbientOcclusionSettings a;
        a.rays = 4;
        a.temporal.enabled = true;
        for (std::uint32_t frame = 0; frame < 2; ++frame) {
            a.frameIndex = frame;
            ao->run(view, a);
        }
    });
    check("AmbientOcclusion::run (voxel)", [&] {
        ao->run(view, {.method = AoMethod::Voxel, .rays = 4, .voxels = &voxelizer->grid()});
    });
    auto gi = std::make_unique<IndirectLight>(*ctx);
    IndirectLightView giView;
    check("IndirectLight::run (half resolution, blur: the albedo bound for the upsampling)", [&] {
        gi->run(view, {.rays = 4, .resolution = AoResolution::Half, .blurRadius = 1});
    });
    check("IndirectLight::run (temporal) and prepare", [&] {
        IndirectLightSettings g;
        g.rays = 4;
        g.temporal.enabled = true;
        gi->prepare(g);
        gi->run(view, g);
    });
    // The view compose reads below comes last: a run replaces the module's images.
    check("IndirectLight::run", [&] {
        IndirectLightSettings g;
        g.rays = 4;
        giView = gi->run(view, g);
    });
    std::unique_ptr<EnvironmentMap> environment;
    check("EnvironmentMap::EnvironmentMap and setLookup", [&] {
        environment = std::make_unique<EnvironmentMap>(*ctx, Image{8, 4, 3, std::vector<float>(96, 1.0f)},
                                                       EnvironmentSettings{8, 2, 8, 0.0f, 0.0f});
        environment->setLookup(2.0f, 0.5f);
    });
    auto ssdo = std::make_unique<DirectionalOcclusion>(*ctx);
    check("DirectionalOcclusion::prepare and run (half resolution, blur, lights, bounce)", [&] {
        DirectionalOcclusionSettings d;
        d.rays = 4;
        d.resolution = AoResolution::Half;
        d.blurRadius = 1;
        d.bounce = true;
        ssdo->prepare(d);
        ssdo->run(view, {environment.get(), s.scene.lights}, d);
    });
    auto media = std::make_unique<Media>(*ctx);
    check("Media::prepare, run (each method; the march at half resolution, blurred) and apply", [&] {
        Medium fog;
        fog.boxMin = glm::vec3(-5.0f);
        fog.boxMax = glm::vec3(5.0f);
        fog.scattering = glm::vec3(0.1f);
        const std::vector<Medium> fogs{fog};
        for (MediaMethod method : {MediaMethod::RayMarch, MediaMethod::Analytic, MediaMethod::Froxel}) {
            MediaSettings m;
            m.method = method;
            m.steps = 8;
            if (method == MediaMethod::RayMarch) { // through the filters
                m.resolution = AoResolution::Half;
                m.blurRadius = 1;
            }
            media->prepare(m);
            const MediaView out = media->run(view, {fogs, s.scene.lights}, m);
            media->apply(out, out.scattering);
        }
    });
    check("GBuffer::render (two depth layers)", [&] {
        GBufferSettings two{40, 32, true, {}};
        two.depthLayers = 2;
        view = gbuffer->render(s.scene, s.camera, two);
    });
    auto visibility = std::make_unique<ScreenVisibility>(*ctx);
    check("ScreenVisibility::trace (Hi-Z, depth peeling)", [&] {
        ScreenTraceSettings t;
        t.march = ScreenMarch::HiZ;
        t.thicknessMode = ScreenThickness::DepthPeeling;
        visibility->trace(view, {{glm::vec3(0.0f, 0.0f, -1.0f), glm::vec3(1.0f, 1.0f, -5.0f)}}, t);
    });
    check("ScreenVisibility::hidden", [&] { visibility->hidden(view, {glm::vec3(0.0f, 0.0f, -3.0f)}, {}); });
    check("ScreenVisibility::~ScreenVisibility", [&] { visibility.reset(); });
    auto shadows = std::make_unique<ShadowMaps>(*ctx);
    const ShadowMapSet* maps = nullptr;
    check("ShadowMaps::render (spot, two cascades)", [&] { maps = &shadows->render(s.scene, s.camera, {64, 2, 0.5f}); });
    check("ShadowMaps::mask (PCF, directional)", [&] { shadows->mask(view, *maps, 2, {}); });
    check("ShadowMaps::mask (moments, spot)", [&] {
        ShadowMaskSettings m;
        m.filter = ShadowFilter::Evsm4;
        shadows->mask(view, *maps, 1, m);
    });
    check("ShadowMaps::render (the point light as paraboloids)", [&] {
        ShadowMapSettings paraboloids{64, 2, 0.5f};
        paraboloids.pointMapping = PointShadowMapping::DualParaboloid;
        shadows->render(s.scene, s.camera, paraboloids);
    });
    check("ShadowMaps::render (reflective shadow maps)", [&] {
        ShadowMapSettings reflective{64, 2, 0.5f};
        reflective.reflective = true;
        shadows->render(s.scene, s.camera, reflective);
    });
    check("ShadowMaps::render (cascades fitted to the depth buffer)",
          [&] { maps = &shadows->render(s.scene, s.camera, {64, 2, 0.5f}, view); });
    check("ShadowMaps::mask (PCSS, spot)", [&] {
        ShadowMaskSettings m;
        m.filter = ShadowFilter::Pcss;
        shadows->mask(view, *maps, 1, m);
    });
    check("GBuffer::render (shadowed by the maps, PCF)", [&] {
        GBufferSettings shadowed{40, 32, true, {}};
        shadowed.shadows = maps;
        view = gbuffer->render(s.scene, s.camera, shadowed);
    });
    check("Media::run (bounded: spot shadow volumes drawn from the camera)", [&] {
        Scene spots = s.scene;
        std::erase_if(spots.lights, [](const Light& l) { return l.type != LightType::Spot; });
        Medium fog;
        fog.boxMin = glm::vec3(-5.0f);
        fog.boxMax = glm::vec3(5.0f);
        fog.scattering = glm::vec3(0.1f);
        const std::vector<Medium> fogs{fog};
        const ShadowMapSet& spotMaps = shadows->render(spots, s.camera, {64});
        MediaSettings m;
        m.method = MediaMethod::Bounded;
        m.steps = 8;
        media->prepare(m);
        media->run(view, {fogs, spots.lights, &spotMaps}, m);
    });
    check("ShadowMaps::~ShadowMaps", [&] { shadows.reset(); });
    auto composer = std::make_unique<Composer>(*ctx);
    TextureView display;
    check("Composer::prepare and GBuffer::prepareAdopt", [&] {
        composer->prepare({});
        HostGBuffer unsignedNormals;
        unsignedNormals.normal = {1, 0, 0, 0}; // not read: only its presence and encoding
        unsignedNormals.normalEncoding = NormalEncoding::Unsigned;
        gbuffer->prepareAdopt(unsignedNormals);
    });
    check("Composer::compose", [&] {
        ComposeSettings c;
        c.toneMapper = ToneMapper::Drago;
        display = composer->compose({view, aoView.ao, giView.radiance}, c);
    });
    check("Composer::drawToHost (multiply)", [&] {
        composer->drawToHost(aoView.ao, {s.hostFramebuffer, 0, 0, 8, 8, HostBlend::Multiply});
    });
    check("AmbientOcclusion::~AmbientOcclusion", [&] { ao.reset(); });
    check("IndirectLight::~IndirectLight", [&] { gi.reset(); });
    check("DirectionalOcclusion::~DirectionalOcclusion", [&] { ssdo.reset(); });
    check("EnvironmentMap::~EnvironmentMap", [&] { environment.reset(); });
    check("Media::~Media", [&] { media.reset(); });
    check("Composer::~Composer", [&] { composer.reset(); });
    check("Voxelizer::~Voxelizer", [&] { voxelizer.reset(); });
    check("GBuffer::~GBuffer", [&] { gbuffer.reset(); });
    check("Context::~Context", [&] { ctx.reset(); });
}

bool isPerUnit(const std::string& key) {
    for (const char* p : {"texture unit", "sampler unit", "image ", "ubo", "ssbo", "atomic counter buffer["})
        if (key.rfind(p, 0) == 0) return true;
    return false;
}

// Items context.hpp lists (and those that follow from them, e.g. the element buffer of the
// bound VAO), excluding per-unit bindings.
bool onObscuraList(const std::string& key) {
    static const char* const notListed[] = {
        "renderbuffer", "program pipeline", "color clear value", "depth clear value",
        "stencil clear value", "line width", "point size", "primitive restart index",
        "patch vertices", "fragment shader derivative hint", "enabled multisample", "enabled line smooth",
        "enabled sample shading", "enabled cube map seamless", "enabled debug output", "debug callback",
        "debug group stack depth", "depth bounds", "exclusive scissor box", "viewport w scale["};
    for (const char* n : notListed)
        if (key.rfind(n, 0) == 0) return false;
    if (key == "transform feedback") return false; // the object binding; its generic buffer binding is listed
    for (const char* indexed : {"viewport[", "scissor box[", "depth range[", "enabled scissor[", "enabled exclusive scissor[",
                                "enabled shading rate image[", "viewport swizzle "})
        if (key.rfind(indexed, 0) == 0) return key.find("[0]") != std::string::npos;
    return true;
}

} // namespace

TEST_CASE("Preserve: every entry point leaves the whole listed host state unchanged", "[state][host-contract]") {
    const bool withDebugCallback = GENERATE(false, true);
    CAPTURE(withDebugCallback);
    test::GlFixture gl(/*debug=*/true);
    HostObjects host;
    // GL errors raised inside our calls arrive here (the debug context reports them).
    std::vector<std::string> messages;
    const DebugCallback collect = [&](const DebugMessage& m) {
        if (m.type == GL_DEBUG_TYPE_ERROR) messages.push_back(m.text);
    };
    StateScene scene;
    if (!withDebugCallback) std::printf("state guard: extensions here with saved state: %s\n", test::guardedExtensionsPresent().c_str());
    setUnusualState(host);
    // The host times the whole sequence with its own GL_TIME_ELAPSED query.
    glBeginQuery(GL_TIME_ELAPSED, host.timeQuery);
    int checked = 0;
    forEachEntryPoint(gl, StatePolicy::Preserve, scene, [&](const std::string& name, const std::function<void()>& call) {
        const test::GlState before = test::captureGlState();
        messages.clear();
        call();
        const auto diff = test::diffGlState(before, test::captureGlState());
        INFO(name << " changed:\n" << [&] { std::string s; for (const auto& d : diff) s += "  " + d + "\n"; return s; }());
        INFO("GL errors inside the call:\n" << [&] { std::string s; for (const auto& m : messages) s += "  " + m + "\n"; return s; }());
        CHECK(diff.empty());
        CHECK(messages.empty());
        CHECK(test::drainGlErrors().empty());
        ++checked;
    }, withDebugCallback ? collect : DebugCallback{});
    glEndQuery(GL_TIME_ELAPSED);
    glBindBuffer(GL_QUERY_BUFFER, 0); // else the result would be written into the host's query buffer
    GLuint64 elapsed = 0;
    glGetQueryObjectui64v(host.timeQuery, GL_QUERY_RESULT_NO_WAIT, &elapsed);
    CHECK(test::drainGlErrors().empty());
    CHECK(checked == 53);
}

TEST_CASE("Preserve: results do not depend on the state the host left", "[state][host-contract]") {
    test::GlFixture gl;
    StateScene scene;
    Context ctx(gl.desc());
    GBuffer gbuffer(ctx);
    const auto renderAll = [&] {
        const GBufferView v = gbuffer.render(scene.scene, scene.camera, {40, 32, true, {}});
        std::vector<Image> images;
        for (const TextureView& t : {v.depth, v.normal, v.albedo, v.directRadiance, gbuffer.positions(v)})
            images.push_back(readTexture(ctx, t));
        return images;
    };
    const auto clean = renderAll();
    HostObjects host;
    setUnusualState(host);
    const auto hostile = renderAll();
    REQUIRE(clean.size() == hostile.size());
    for (std::size_t i = 0; i < clean.size(); ++i) {
        std::size_t differing = 0, first = 0;
        for (std::size_t k = clean[i].pixels.size(); k-- > 0;)
            if (clean[i].pixels[k] != hostile[i].pixels[k]) ++differing, first = k;
        INFO("image " << i << ": " << differing << " values differ, first at " << first << " ("
                      << (differing ? clean[i].pixels[first] : 0.0f) << " vs " << (differing ? hostile[i].pixels[first] : 0.0f) << ")");
        CHECK(differing == 0);
    }
}

TEST_CASE("Clobber: listed state is left at GL initial values nothing else is touched", "[state][host-contract]") {
    test::GlFixture gl;
    const test::GlState initial = test::captureGlState();
    HostObjects host;
    StateScene scene;
    forEachEntryPoint(gl, StatePolicy::Clobber, scene, [&](const std::string& name, const std::function<void()>& call) {
        setUnusualState(host);
        const test::GlState before = test::captureGlState();
        call();
        const test::GlState after = test::captureGlState();
        CHECK(test::drainGlErrors().empty());
        // Creating and destroying objects issues no state change under either policy.
        if (name == "Context::Context" || name.find("::~") != std::string::npos) {
            INFO(name);
            CHECK(test::diffGlState(before, after).empty());
            return;
        }
        int unitsReset = 0;
        for (const auto& [key, value] : after) {
            INFO(name << ": " << key);
            if (isPerUnit(key) && value != before.at(key) && value == initial.at(key)) ++unitsReset;
            if (key == "viewport[0]" || key == "scissor box[0]") continue; // documented: last values we set
            if (isPerUnit(key)) CHECK((value == before.at(key) || value == initial.at(key)));
            else if (key.find("stencil") != std::string::npos && key.find("mask") != std::string::npos)
                CHECK(value == std::vector<double>{255.0}); // documented: 0xFF, all bits of an 8-bit stencil
            else if (onObscuraList(key)) CHECK(value == initial.at(key));
            else CHECK(value == before.at(key));
        }
        // The G-buffer pass binds a frame block, a light buffer and textures: under Clobber
        // those units must come back unbound, not keep our objects.
        if (name.rfind("GBuffer::render", 0) == 0 && name.find("throwing") == std::string::npos) CHECK(unitsReset >= 2);
    });
}

TEST_CASE("Debug output: our messages go to our callback and the host's callback is restored", "[state][debug]") {
    test::GlFixture gl(/*debug=*/true);
    // Drivers may add notifications of their own (NVIDIA 580: where a buffer lives), and
    // deliver the host's asynchronously: those are not messages of ours or the host's.
    struct Counter {
        int messages = 0;
        static bool driverNote(GLenum source, GLenum severity) {
            return source == GL_DEBUG_SOURCE_API && severity == GL_DEBUG_SEVERITY_NOTIFICATION;
        }
        static void GLAD_API_PTR callback(GLenum source, GLenum, GLuint, GLenum severity, GLsizei, const GLchar*,
                                          const void* user) {
            if (!driverNote(source, severity)) ++static_cast<Counter*>(const_cast<void*>(user))->messages;
        }
    } hostCounter;
    glDebugMessageCallback(&Counter::callback, &hostCounter);
    glEnable(GL_DEBUG_OUTPUT);
    StateScene scene;
    SECTION("without a debugOutput callback the host sees our debug groups") {
        Context ctx(gl.desc());
        GBuffer gbuffer(ctx);
        gbuffer.render(scene.scene, scene.camera, {16, 16, true, {}});
        CHECK(hostCounter.messages >= 2); // push and pop of "gbuffer.render"
    }
    SECTION("with one, messages during our calls go to it, and the host's callback is back afterwards") {
        int ours = 0;
        ContextDesc desc = gl.desc();
        std::string first;
        desc.debugOutput = [&](const DebugMessage& m) {
            if (Counter::driverNote(m.source, m.severity)) return;
            if (ours++ == 0) first = m.text;
        };
        Context ctx(desc);
        GBuffer gbuffer(ctx);
        const test::GlState before = test::captureGlState();
        gbuffer.render(scene.scene, scene.camera, {16, 16, true, {}});
        CHECK(test::diffGlState(before, test::captureGlState()).empty());
        CHECK(hostCounter.messages == 0);
        glDebugMessageInsert(GL_DEBUG_SOURCE_APPLICATION, GL_DEBUG_TYPE_MARKER, 1, GL_DEBUG_SEVERITY_NOTIFICATION, -1, "host");
        CHECK(hostCounter.messages == 1);
        INFO("first message: " << first);
        CHECK(ours == 0); // nothing in our calls raised a message
    }
}

TEST_CASE("Preserve: a program the host deleted while current leaves program 0 current and no GL error",
          "[state][host-contract]") {
    // glDeleteProgram on the current program only flags it (GL 4.5, 7.3); it goes when
    // another is bound, as ours must be. Restoring its name raised GL_INVALID_VALUE in the
    // host's context and left our last program current.
    test::GlFixture gl;
    Context ctx(gl.desc());
    GBuffer gbuffer(ctx);
    AmbientOcclusion ao(ctx);
    StateScene scene;
    const GBufferView view = gbuffer.render(scene.scene, scene.camera, {16, 16, true, {}});
    ao.run(view, {});
    const char* cs = "#version 450 core\nlayout(local_size_x = 1) in; void main() {}\n";
    const GLuint shader = glCreateShader(GL_COMPUTE_SHADER);
    glShaderSource(shader, 1, &cs, nullptr);
    glCompileShader(shader);
    const GLuint program = glCreateProgram();
    glAttachShader(program, shader);
    glLinkProgram(program);
    glDeleteShader(shader);
    glUseProgram(program);
    glDeleteProgram(program);
    GLint flagged = GL_FALSE;
    glGetProgramiv(program, GL_DELETE_STATUS, &flagged);
    REQUIRE(flagged == GL_TRUE); // the premise: flagged, still current
    REQUIRE(test::drainGlErrors().empty());
    ao.run(view, {});
    GLint current = -1;
    glGetIntegerv(GL_CURRENT_PROGRAM, &current);
    CHECK(current == 0);
    CHECK_FALSE(glIsProgram(program)); // deleted, as GL does once it is no longer current
    CHECK(test::drainGlErrors().empty());
}

TEST_CASE("An active transform feedback is refused before any GL work", "[state][bad-input]") {
    test::GlFixture gl;
    Context ctx(gl.desc());
    GBuffer gbuffer(ctx);
    StateScene scene;
    // Capture into a buffer with a trivial program that has a varying.
    const char* vs = "#version 450 core\nout float v; void main() { v = 1.0; gl_Position = vec4(0); }\n";
    const GLuint program = glCreateProgram();
    const GLuint s = glCreateShader(GL_VERTEX_SHADER);
    glShaderSource(s, 1, &vs, nullptr);
    glCompileShader(s);
    glAttachShader(program, s);
    const char* varyings[] = {"v"};
    glTransformFeedbackVaryings(program, 1, varyings, GL_INTERLEAVED_ATTRIBS);
    glLinkProgram(program);
    GLuint buffer = 0;
    glCreateBuffers(1, &buffer);
    glNamedBufferData(buffer, 1024, nullptr, GL_DYNAMIC_COPY);
    glBindBufferBase(GL_TRANSFORM_FEEDBACK_BUFFER, 0, buffer);
    glUseProgram(program);
    glEnable(GL_RASTERIZER_DISCARD);
    glBeginTransformFeedback(GL_POINTS);
    const test::GlState before = test::captureGlState();
    try {
        gbuffer.render(scene.scene, scene.camera, {16, 16, true, {}});
        FAIL("render ran during active transform feedback");
    } catch (const Error& e) {
        CHECK(e.code() == ErrorCode::InvalidState);
        CHECK_THAT(e.what(), Catch::Contains("transform feedback"));
    }
    CHECK(test::diffGlState(before, test::captureGlState()).empty());
    glEndTransformFeedback();
    glDisable(GL_RASTERIZER_DISCARD);
    glUseProgram(0);
    glDeleteProgram(program);
    glDeleteShader(s);
    glDeleteBuffers(1, &buffer);
    CHECK(test::drainGlErrors().empty());
}
