// Bad input: every case gives an obscura::Error with the right code and a message naming what
// was wrong, leaves no GL error pending and no GL object behind.
#include "gl_fixture.hpp"
#include "obscura/obscura.hpp"
#include "scene_builders.hpp"

#include <catch2/catch.hpp>

#include <algorithm>
#include <climits>
#include <cmath>
#include <functional>

using namespace obscura;

namespace {

struct BadInputFixture {
    test::GlFixture gl;
    Context ctx{gl.desc()};
    GBuffer gbuffer{ctx};
    Scene scene = test::quadScene({{{{{-1, 0, -1}, {-1, 0, 1}, {1, 0, 1}, {1, 0, -1}}}}});
    Camera camera = Camera::perspective({{0, 2, 2}, {0, 0, 0}, {0, 1, 0}}, 1.0f, 1.0f, 0.1f, 10.0f);
    GBufferView good;

    BadInputFixture() {
        // Warm up, so that caches a successful call creates are not mistaken for leaks.
        good = gbuffer.render(scene, camera, {16, 16, true, {}});
        gbuffer.positions(good);
        HostGBuffer host;
        host.depth = good.depth;
        gbuffer.adopt(host, camera);
    }

    // Runs `call`, which must throw an Error with `code` whose message contains `needle`.
    void expectError(const std::function<void()>& call, ErrorCode code, const std::string& needle) {
        // Timer queries whose results are still pending are not reused yet, so a GPU that runs
        // behind (NVIDIA, unlike llvmpipe) would add pool queries that are not leaks: wait.
        ctx.profiler().statistics(/*wait=*/true);
        const auto objectsBefore = test::liveGlObjects();
        const std::size_t countBefore = ctx.liveObjectCount();
        try {
            call();
            FAIL("no error; expected one mentioning \"" << needle << "\"");
        } catch (const Error& e) {
            INFO(e.what());
            CHECK(e.code() == code);
            CHECK_THAT(e.what(), Catch::Contains(needle));
        }
        CHECK(test::drainGlErrors().empty());
        CHECK(test::liveGlObjects() == objectsBefore);
        CHECK(ctx.liveObjectCount() == countBefore);
    }
};

GLuint hostTexture(GLenum format, int w, int h) {
    GLuint t = 0;
    glCreateTextures(GL_TEXTURE_2D, 1, &t);
    glTextureStorage2D(t, 1, format, w, h);
    return t;
}

} // namespace

TEST_CASE_METHOD(BadInputFixture, "Zero negative and huge target sizes are refused", "[bad-input]") {
    const int max = ctx.info().maxTextureSize;
    for (auto [w, h] : {std::pair{0, 16}, std::pair{16, 0}, std::pair{-4, 16}, std::pair{max + 1, 16},
                        std::pair{16, INT_MAX}}) {
        CAPTURE(w, h);
        expectError([&] { gbuffer.render(scene, camera, {w, h, true, {}}); }, ErrorCode::InvalidArgument,
                    "GL_MAX_TEXTURE_SIZE");
    }
}

TEST_CASE_METHOD(BadInputFixture, "NaN and Inf in matrices lights and materials are refused", "[bad-input]") {
    const float nan = std::nanf(""), inf = INFINITY;
    Camera c = camera;
    c.view[1][2] = nan;
    expectError([&] { gbuffer.render(scene, c, {16, 16, true, {}}); }, ErrorCode::InvalidArgument, "Camera::view");
    c = camera;
    c.projection[0][0] = inf;
    expectError([&] { gbuffer.render(scene, c, {16, 16, true, {}}); }, ErrorCode::InvalidArgument, "Camera::projection");
    Scene s = scene;
    s.meshes[0].model[3][0] = nan;
    expectError([&] { gbuffer.render(s, camera, {16, 16, true, {}}); }, ErrorCode::InvalidArgument, "meshes[0].model");
    s = scene;
    auto data = std::make_shared<MeshData>(*s.meshes[0].data);
    data->positions[2].y = nan;
    s.meshes[0].data = data;
    expectError([&] { gbuffer.render(s, camera, {16, 16, true, {}}); }, ErrorCode::InvalidArgument, "position 2");
    s = scene;
    Light l;
    l.position.x = nan;
    s.lights.push_back(l);
    expectError([&] { gbuffer.render(s, camera, {16, 16, true, {}}); }, ErrorCode::InvalidArgument, "lights[0].position");
    s.lights[0] = Light{};
    s.lights[0].intensity = inf;
    expectError([&] { gbuffer.render(s, camera, {16, 16, true, {}}); }, ErrorCode::InvalidArgument, "intensity");
    s = scene;
    s.materials[0].albedo = {0.5f, nan, 0.5f};
    expectError([&] { gbuffer.render(s, camera, {16, 16, true, {}}); }, ErrorCode::InvalidArgument, "materials[0].albedo");
    expectError([] { Camera::perspective({{0, 0, 0}, {0, 0, 0}, {0, 1, 0}}, 1.0f, 1.0f, 0.1f, 10.0f); },
                ErrorCode::InvalidArgument, "eye and target");
    expectError([] { Camera::perspective({{0, 0, 1}, {0, 0, 0}, {0, 1, 0}}, 1.0f, 1.0f, 0.0f, 10.0f); },
                ErrorCode::InvalidArgument, "near");
    expectError([] { Camera::perspective({{0, 0, 1}, {0, 0, 0}, {0, 1, 0}}, 1.0f, 1.0f, 0.1f, INFINITY); },
                ErrorCode::InvalidArgument, "Reversed");
}

TEST_CASE_METHOD(BadInputFixture, "Inconsistent meshes and material indices are refused", "[bad-input]") {
    Scene s = scene;
    s.meshes[0].material = 3;
    expectError([&] { gbuffer.render(s, camera, {16, 16, true, {}}); }, ErrorCode::InvalidArgument, "material");
    s = scene;
    auto data = std::make_shared<MeshData>(*s.meshes[0].data);
    data->indices.push_back(99);
    s.meshes[0].data = data;
    expectError([&] { gbuffer.render(s, camera, {16, 16, true, {}}); }, ErrorCode::InvalidArgument, "multiple of 3");
    data->indices = {0, 1, 7};
    expectError([&] { gbuffer.render(s, camera, {16, 16, true, {}}); }, ErrorCode::InvalidArgument, ">= 4 positions");
    data->indices = {0, 1, 2};
    data->normals.pop_back();
    expectError([&] { gbuffer.render(s, camera, {16, 16, true, {}}); }, ErrorCode::InvalidArgument, "normals");
    s = scene;
    MeshRef ref;
    ref.position = {12345, 0, 12, 3, GL_FLOAT, false};
    ref.count = 3;
    s.meshRefs.push_back(ref);
    expectError([&] { gbuffer.render(s, camera, {16, 16, true, {}}); }, ErrorCode::InvalidArgument, "not a GL buffer");
    s.meshRefs[0].vao = 777;
    expectError([&] { gbuffer.render(s, camera, {16, 16, true, {}}); }, ErrorCode::InvalidArgument, "not a GL vertex array");
}

TEST_CASE_METHOD(BadInputFixture, "Host mesh ranges are checked against the host buffers", "[bad-input]") {
    // 3 vertices (36 bytes) and 3 16-bit indices (6 bytes).
    const float vertices[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    const std::uint16_t indices[3] = {0, 1, 2};
    GLuint buffers[2];
    glCreateBuffers(2, buffers);
    glNamedBufferData(buffers[0], sizeof vertices, vertices, GL_STATIC_DRAW);
    glNamedBufferData(buffers[1], sizeof indices, indices, GL_STATIC_DRAW);
    MeshRef valid;
    valid.position = {buffers[0], 0, 12, 3, GL_FLOAT, false};
    valid.count = 3;
    Scene s = scene;
    s.meshRefs = {valid};
    gbuffer.render(s, camera, {16, 16, true, {}}); // the valid mesh renders
    const auto refuse = [&](MeshRef ref, const std::string& needle) {
        s.meshRefs = {ref};
        expectError([&] { gbuffer.render(s, camera, {16, 16, true, {}}); }, ErrorCode::InvalidArgument, needle);
    };
    MeshRef r = valid;
    r.count = 6; // 6 vertices of 12 bytes need 72 bytes
    refuse(r, "reads up to byte 72 of a buffer of 36 bytes");
    r = valid;
    r.position.offset = 30;
    refuse(r, "reads up to byte");
    r = valid;
    r.count = 0x80000001u; // > INT_MAX
    refuse(r, "INT_MAX");
    r = valid;
    r.position.stride = 1u << 20;
    refuse(r, "GL_MAX_VERTEX_ATTRIB_STRIDE");
    r = valid;
    r.position.type = GL_INT_2_10_10_10_REV;
    refuse(r, "needs 4 components");
    r = valid;
    r.indexBuffer = buffers[1];
    r.indexType = GL_UNSIGNED_SHORT;
    r.count = 6;
    refuse(r, "overrun the index buffer of 6 bytes");
    r.count = 3;
    r.indexOffset = 1;
    refuse(r, "not a multiple of the index size");
    r.indexOffset = 0;
    r.indexType = GL_FLOAT;
    refuse(r, "indexType");
    glDeleteBuffers(2, buffers);
}

TEST_CASE_METHOD(BadInputFixture, "Wrong texture formats names and sizes are refused", "[bad-input]") {
    const GLuint rgba8 = hostTexture(GL_RGBA8, 16, 16);
    const GLuint depth = hostTexture(GL_DEPTH_COMPONENT32F, 16, 16);
    const GLuint depthOdd = hostTexture(GL_DEPTH_COMPONENT24, 8, 8);
    const GLuint rg16f = hostTexture(GL_RG16F, 16, 16);
    const GLuint stencilled = hostTexture(GL_DEPTH24_STENCIL8, 16, 16);
    glTextureParameteri(stencilled, GL_DEPTH_STENCIL_TEXTURE_MODE, GL_STENCIL_INDEX);
    GLuint multisample = 0;
    glCreateTextures(GL_TEXTURE_2D_MULTISAMPLE, 1, &multisample);
    glTextureStorage2DMultisample(multisample, 4, GL_DEPTH_COMPONENT32F, 16, 16, GL_TRUE);
    const auto adopt = [&](GLuint d, GLuint n, NormalEncoding enc = NormalEncoding::Signed) {
        HostGBuffer h;
        h.depth = {d, 0, 0, 0};
        h.normal = {n, 0, 0, 0};
        h.normalEncoding = enc;
        gbuffer.adopt(h, camera);
    };
    expectError([&] { adopt(rgba8, 0); }, ErrorCode::InvalidArgument, "depth format");
    expectError([&] { adopt(0, 0); }, ErrorCode::InvalidArgument, "not a GL texture");
    expectError([&] { adopt(4242, 0); }, ErrorCode::InvalidArgument, "not a GL texture");
    expectError([&] { adopt(multisample, 0); }, ErrorCode::InvalidArgument, "GL_TEXTURE_2D");
    expectError([&] { adopt(stencilled, 0); }, ErrorCode::InvalidArgument, "GL_DEPTH_STENCIL_TEXTURE_MODE");
    expectError([&] { adopt(depth, depth); }, ErrorCode::InvalidArgument, "GL_DEPTH_COMPONENT32F");
    expectError([&] { adopt(depth, rgba8); }, ErrorCode::InvalidArgument, "NormalEncoding::Signed");
    expectError([&] { adopt(depth, rg16f); }, ErrorCode::InvalidArgument, "GL_RG16F");
    // No sign bit: a normal's negative components would clamp to 0.
    const GLuint r11g11b10 = hostTexture(GL_R11F_G11F_B10F, 16, 16), rgb9e5 = hostTexture(GL_RGB9_E5, 16, 16);
    expectError([&] { adopt(depth, r11g11b10); }, ErrorCode::InvalidArgument, "signed float");
    expectError([&] { adopt(depth, rgb9e5); }, ErrorCode::InvalidArgument, "GL_RGB9_E5");
    // Fewer than 4 bits in a channel, as the GL stores it (it may widen a requested format).
    const GLuint r3g3b2 = hostTexture(GL_R3_G3_B2, 16, 16);
    GLint r3Bits = 32; // its coarsest channel, as adopt() counts
    for (const GLenum channel : {GL_TEXTURE_RED_SIZE, GL_TEXTURE_GREEN_SIZE, GL_TEXTURE_BLUE_SIZE}) {
        GLint size = 0;
        glGetTextureLevelParameteriv(r3g3b2, 0, channel, &size);
        r3Bits = std::min(r3Bits, size);
    }
    INFO("GL_R3_G3_B2 stored with " << r3Bits << " bits in its coarsest channel");
    if (r3Bits < 4) expectError([&] { adopt(depth, r3g3b2, NormalEncoding::Unsigned); }, ErrorCode::InvalidArgument, "at least 4 bits");
    else CHECK_NOTHROW(adopt(depth, r3g3b2, NormalEncoding::Unsigned));
    for (GLuint t : {r11g11b10, rgb9e5, r3g3b2}) glDeleteTextures(1, &t);
    expectError([&] { adopt(depthOdd, rgba8, NormalEncoding::Unsigned); }, ErrorCode::InvalidArgument, "8x8");
    const GLuint rgba8ui = hostTexture(GL_RGBA8UI, 16, 16);
    const auto adoptLit = [&](GLuint albedo, GLuint radiance) {
        HostGBuffer h;
        h.depth = {depth, 0, 0, 0};
        h.albedo = {albedo, 0, 0, 0};
        h.directRadiance = {radiance, 0, 0, 0};
        gbuffer.adopt(h, camera);
    };
    expectError([&] { adoptLit(rg16f, 0); }, ErrorCode::InvalidArgument, "HostGBuffer::albedo has format GL_RG16F");
    expectError([&] { adoptLit(rgba8ui, 0); }, ErrorCode::InvalidArgument, "HostGBuffer::albedo has format");
    expectError([&] { adoptLit(depth, 0); }, ErrorCode::InvalidArgument, "HostGBuffer::albedo has format");
    expectError([&] { adoptLit(0, rgba8); }, ErrorCode::InvalidArgument, "HostGBuffer::directRadiance has format GL_RGBA8");
    const GLuint small = hostTexture(GL_RGBA16F, 8, 8);
    expectError([&] { adoptLit(rgba8, small); }, ErrorCode::InvalidArgument, "HostGBuffer::directRadiance is 8x8");
    expectError([&] { adoptLit(4242, 0); }, ErrorCode::InvalidArgument, "not a GL texture");
    const auto adoptBack = [&](GLuint back) {
        HostGBuffer h;
        h.depth = {depth, 0, 0, 0};
        h.backDepth = {back, 0, 0, 0};
        gbuffer.adopt(h, camera);
    };
    expectError([&] { adoptBack(rgba8); }, ErrorCode::InvalidArgument, "HostGBuffer::backDepth must have a depth format");
    expectError([&] { adoptBack(depthOdd); }, ErrorCode::InvalidArgument, "HostGBuffer::backDepth is 8x8");
    expectError([&] { adoptBack(stencilled); }, ErrorCode::InvalidArgument, "HostGBuffer::backDepth samples stencil");
    expectError([&] { adoptBack(multisample); }, ErrorCode::InvalidArgument, "GL_TEXTURE_2D");
    expectError([&] { adoptBack(4242); }, ErrorCode::InvalidArgument, "not a GL texture");
    expectError([&] { adoptBack(depth); }, ErrorCode::InvalidArgument, "HostGBuffer::backDepth is HostGBuffer::depth");
    for (GLuint t : {rgba8ui, small}) glDeleteTextures(1, &t);
    expectError([&] { readTexture(ctx, {multisample, 0, 16, 16}); }, ErrorCode::InvalidArgument, "GL_TEXTURE_2D");
    GLuint mipmapped = 0;
    glCreateTextures(GL_TEXTURE_2D, 1, &mipmapped);
    glTextureStorage2D(mipmapped, 2, GL_DEPTH_COMPONENT32F, 16, 16);
    glTextureParameteri(mipmapped, GL_TEXTURE_BASE_LEVEL, 1);
    expectError([&] { adopt(mipmapped, 0); }, ErrorCode::InvalidArgument, "GL_TEXTURE_BASE_LEVEL");
    glDeleteTextures(1, &mipmapped);
    Scene s = scene;
    s.materials[0].albedoTexture = depth;
    expectError([&] { gbuffer.render(s, camera, {16, 16, true, {}}); }, ErrorCode::InvalidArgument, "albedoTexture");
    for (GLuint t : {rgba8, depth, depthOdd, rg16f, stencilled, multisample}) glDeleteTextures(1, &t);
}

TEST_CASE_METHOD(BadInputFixture, "Light and camera parameters outside their ranges are refused", "[bad-input]") {
    Scene s = scene;
    Light spot;
    spot.type = LightType::Spot;
    spot.innerAngle = 0.8f;
    spot.outerAngle = 0.5f;
    s.lights.push_back(spot);
    expectError([&] { gbuffer.render(s, camera, {16, 16, true, {}}); }, ErrorCode::InvalidArgument, "innerAngle");
    s.lights[0].innerAngle = 0.2f;
    s.lights[0].direction = glm::vec3(0.0f);
    expectError([&] { gbuffer.render(s, camera, {16, 16, true, {}}); }, ErrorCode::InvalidArgument, "direction");
    s.lights[0] = Light{};
    s.lights[0].radius = -1.0f;
    expectError([&] { gbuffer.render(s, camera, {16, 16, true, {}}); }, ErrorCode::InvalidArgument, "radius");
    expectError([&] { gbuffer.render(scene, camera, {16, 16, true, {-1.0f, 0.0f, 0.0f}}); }, ErrorCode::InvalidArgument,
                "background");
    expectError([&] { gbuffer.render(scene, camera, {16, 16, true, {1e6f, 0.0f, 0.0f}}); }, ErrorCode::InvalidArgument,
                "65504");
    Light bright;
    bright.color = glm::vec3(1e30f);
    bright.intensity = 1e30f;
    Scene s2 = scene;
    s2.lights.push_back(bright);
    expectError([&] { gbuffer.render(s2, camera, {16, 16, true, {}}); }, ErrorCode::InvalidArgument, "float range");
    Camera skewed = camera;
    skewed.projection[1][0] = 0.3f;
    expectError([&] { gbuffer.render(scene, skewed, {16, 16, true, {}}); }, ErrorCode::InvalidArgument, "shear");
    // A reversed-Z [0,1] projection declared as [-1,1] puts depth 0 behind the camera.
    Camera wrongClip = Camera::perspective({{0, 2, 2}, {0, 0, 0}, {0, 1, 0}}, 1.0f, 1.0f, 0.1f, 10.0f, DepthMode::Reversed);
    wrongClip.clipDepth = ClipDepth::NegativeOneToOne;
    expectError([&] { gbuffer.render(scene, wrongClip, {16, 16, true, {}}); }, ErrorCode::InvalidArgument, "ClipDepth");
    // An integer outside the enumerators was taken as NegativeOneToOne by every reader of it.
    Camera unknownClip = camera;
    unknownClip.clipDepth = static_cast<ClipDepth>(2);
    expectError([&] { gbuffer.render(scene, unknownClip, {16, 16, true, {}}); }, ErrorCode::InvalidArgument,
                "Camera::clipDepth");
    HostGBuffer host;
    host.depth = good.depth;
    expectError([&] { gbuffer.adopt(host, unknownClip); }, ErrorCode::InvalidArgument, "Camera::clipDepth");
}

TEST_CASE_METHOD(BadInputFixture, "Host normal encodings and spaces outside their enumerators and sRGB normals are refused",
                 "[bad-input]") {
    // Before, an unknown space was taken as View and an unknown encoding refused with the
    // Unsigned formats' advice; sRGB normals passed as Unsigned ones, which the sampler
    // decodes (0.5 reads as 0.214), bending every normal.
    const GLuint rgba8 = hostTexture(GL_RGBA8, 16, 16), srgb = hostTexture(GL_SRGB8_ALPHA8, 16, 16);
    HostGBuffer host;
    host.depth = good.depth;
    host.normal = {rgba8, 0, 0, 0};
    host.normalEncoding = NormalEncoding::Unsigned;
    CHECK_NOTHROW(gbuffer.adopt(host, camera)); // the control: the same with a plain RGBA8
    HostGBuffer bad = host;
    bad.normalSpace = static_cast<NormalSpace>(2);
    expectError([&] { gbuffer.adopt(bad, camera); }, ErrorCode::InvalidArgument, "HostGBuffer::normalSpace");
    bad = host;
    bad.normalEncoding = static_cast<NormalEncoding>(3);
    expectError([&] { gbuffer.adopt(bad, camera); }, ErrorCode::InvalidArgument, "HostGBuffer::normalEncoding");
    bad = host;
    bad.normal = {srgb, 0, 0, 0};
    expectError([&] { gbuffer.adopt(bad, camera); }, ErrorCode::InvalidArgument, "GL_SRGB8_ALPHA8");
    // The unsized sRGB format (glTexImage2D keeps it as given) is decoded as well.
    GLuint unsizedSrgb = 0;
    glGenTextures(1, &unsizedSrgb);
    glBindTexture(GL_TEXTURE_2D, unsizedSrgb);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_SRGB_ALPHA, 16, 16, 0, GL_RGBA, GL_UNSIGNED_BYTE, nullptr);
    glBindTexture(GL_TEXTURE_2D, 0);
    bad.normal = {unsizedSrgb, 0, 0, 0};
    expectError([&] { gbuffer.adopt(bad, camera); }, ErrorCode::InvalidArgument, "HostGBuffer::normal has format");
    glDeleteTextures(1, &unsizedSrgb);
    glDeleteTextures(1, &rgba8);
    glDeleteTextures(1, &srgb);
}

TEST_CASE_METHOD(BadInputFixture, "A host texture described other than GL has it is refused", "[bad-input]") {
    // Before, only `name` was read: a host copying a snippet's GL_SRGB8_ALPHA8 for its RGBA8
    // albedo, or last frame's size, was accepted silently. A field left 0 takes GL's.
    const GLuint depth = hostTexture(GL_DEPTH_COMPONENT24, 16, 16), normal = hostTexture(GL_RGBA16F, 16, 16),
                 albedo = hostTexture(GL_RGBA8, 16, 16), rgb16f = hostTexture(GL_RGB16F, 16, 16);
    HostGBuffer host;
    host.depth = {depth, GL_DEPTH_COMPONENT24, 16, 16};
    host.normal = {normal, GL_RGBA16F, 16, 16};
    host.albedo = {albedo, GL_RGBA8, 16, 16};
    CHECK_NOTHROW(gbuffer.adopt(host, camera)); // the control: described as it is
    HostGBuffer bare = host;
    bare.depth = {depth, 0, 0, 0};
    bare.normal = {normal, 0, 16, 0};
    CHECK_NOTHROW(gbuffer.adopt(bare, camera));
    HostGBuffer bad = host;
    bad.depth.internalFormat = GL_DEPTH_COMPONENT32F;
    expectError([&] { gbuffer.adopt(bad, camera); }, ErrorCode::InvalidArgument,
                "HostGBuffer::depth.internalFormat says GL_DEPTH_COMPONENT32F but texture " + std::to_string(depth) +
                    " is GL_DEPTH_COMPONENT24");
    bad = host;
    bad.normal.width = 32;
    expectError([&] { gbuffer.adopt(bad, camera); }, ErrorCode::InvalidArgument, "HostGBuffer::normal.width says 32");
    bad = host;
    bad.albedo.height = 8;
    expectError([&] { gbuffer.adopt(bad, camera); }, ErrorCode::InvalidArgument, "HostGBuffer::albedo.height says 8");
    bad = host;
    bad.albedo.internalFormat = GL_SRGB8_ALPHA8;
    expectError([&] { gbuffer.adopt(bad, camera); }, ErrorCode::InvalidArgument, "albedo.internalFormat says GL_SRGB8_ALPHA8");
    // Normals read in place: view space only, no deviation, a float RGBA format (alpha holds
    // the bound); the deviation's range.
    bad = host;
    bad.normalEncoding = NormalEncoding::ViewContract;
    CHECK_NOTHROW(gbuffer.adopt(bad, camera));
    bad.normalSpace = NormalSpace::World;
    expectError([&] { gbuffer.adopt(bad, camera); }, ErrorCode::InvalidArgument, "NormalSpace::View");
    bad.normalSpace = NormalSpace::View;
    bad.normalDeviation = 0.1f;
    expectError([&] { gbuffer.adopt(bad, camera); }, ErrorCode::InvalidArgument, "normalDeviation 0");
    bad.normalDeviation = 0.0f;
    bad.normal = {rgb16f, 0, 0, 0};
    expectError([&] { gbuffer.adopt(bad, camera); }, ErrorCode::InvalidArgument, "NormalEncoding::ViewContract");
    for (const float deviation : {-0.1f, 1.6f, NAN}) {
        bad = host;
        bad.normalDeviation = deviation;
        expectError([&] { gbuffer.adopt(bad, camera); }, ErrorCode::InvalidArgument, "HostGBuffer::normalDeviation");
    }
    for (GLuint t : {depth, normal, albedo, rgb16f}) glDeleteTextures(1, &t);
}

TEST_CASE_METHOD(BadInputFixture, "A view whose textures the host changed after adopt, or built by hand, is refused by "
                                  "every pass that samples it",
                 "[bad-input][host]") {
    // adopt() checks the host's textures, but a GBufferView is plain data and its textures
    // stay the host's: between adopt and a run the host may switch a depth-stencil texture to
    // stencil sampling or move its base level, and a view may be built by hand. Compose
    // refused such inputs; the screen-space passes (AO, indirect light, screen visibility, the
    // shadow maps' depth range and masks) and positions() read them as they were, undefined
    // values there.
    const GLuint depthStencil = hostTexture(GL_DEPTH24_STENCIL8, 16, 16);
    const GLuint mipmapped = [] {
        GLuint t = 0;
        glCreateTextures(GL_TEXTURE_2D, 1, &t);
        glTextureStorage2D(t, 2, GL_RGBA16F, 16, 16);
        return t;
    }();
    const GLuint ids = hostTexture(GL_RGBA16UI, 16, 16), colour = hostTexture(GL_RGBA16F, 16, 16);
    const GLuint colourUnorm = hostTexture(GL_RGBA8, 16, 16), mono = hostTexture(GL_R16F, 16, 16);
    HostGBuffer host;
    host.depth = {depthStencil, 0, 0, 0};
    host.albedo = {colour, 0, 0, 0};
    host.directRadiance = {colour, 0, 0, 0};
    const GBufferView adopted = gbuffer.adopt(host, camera);
    AmbientOcclusion ao(ctx);
    IndirectLight gi(ctx);
    ScreenVisibility visibility(ctx);
    ShadowMaps shadows(ctx);
    Scene lit = scene;
    Light sun; // directional: its cascades are fitted to the view's depth range, which reads it
    sun.type = LightType::Directional;
    sun.direction = glm::normalize(glm::vec3(0.3f, -1.0f, 0.2f));
    lit.lights = {sun};
    const std::vector<ScreenSegment> segment = {{{0, 0, -1}, {0, 0, -2}}};
    const ShadowMapSettings maps{64, 1, 0.5f};
    // Warm up, so that the shaders and images of a successful run are not counted as leaks.
    ao.run(adopted, {});
    gi.run(adopted, {});
    visibility.trace(adopted, segment, {});
    gbuffer.positions(adopted);
    shadows.mask(adopted, shadows.render(lit, camera, maps, adopted), 0, {});
    const auto refusedEverywhere = [&](const GBufferView& view, const std::string& needle, bool positionsToo) {
        expectError([&] { ao.run(view, {}); }, ErrorCode::InvalidArgument, needle);
        expectError([&] { gi.run(view, {}); }, ErrorCode::InvalidArgument, needle);
        expectError([&] { visibility.trace(view, segment, {}); }, ErrorCode::InvalidArgument, needle);
        expectError([&] { shadows.render(lit, camera, maps, view); }, ErrorCode::InvalidArgument, needle);
        const ShadowMapSet& set = shadows.render(lit, camera, maps); // without the view: accepted
        expectError([&] { shadows.mask(view, set, 0, {}); }, ErrorCode::InvalidArgument, needle);
        if (positionsToo) expectError([&] { gbuffer.positions(view); }, ErrorCode::InvalidArgument, needle);
    };
    glTextureParameteri(depthStencil, GL_DEPTH_STENCIL_TEXTURE_MODE, GL_STENCIL_INDEX);
    refusedEverywhere(adopted, "GBufferView::depth samples stencil", true);
    glTextureParameteri(depthStencil, GL_DEPTH_STENCIL_TEXTURE_MODE, GL_DEPTH_COMPONENT);
    CHECK_NOTHROW(ao.run(adopted, {})); // back as adopted: accepted again
    GBufferView byHand = adopted;
    byHand.normal = {ids, GL_RGBA16UI, 16, 16};
    refusedEverywhere(byHand, "GBufferView::normal has format", false);
    // Normals are read as signed vectors: an unsigned normalized format (what adopt() decodes
    // with NormalEncoding::Unsigned into the view's own) reads n * 0.5 + 0.5 as n.
    byHand.normal = {colourUnorm, GL_RGBA8, 16, 16};
    refusedEverywhere(byHand, "GBufferView::normal has format GL_RGBA8", false);
    byHand = adopted;
    byHand.normal = {mipmapped, GL_RGBA16F, 16, 16};
    glTextureParameteri(mipmapped, GL_TEXTURE_BASE_LEVEL, 1);
    refusedEverywhere(byHand, "GL_TEXTURE_BASE_LEVEL", false);
    byHand = adopted;
    byHand.albedo = {ids, GL_RGBA16UI, 16, 16};
    expectError([&] { gi.run(byHand, {}); }, ErrorCode::InvalidArgument, "GBufferView::albedo has format");
    byHand = adopted;
    byHand.directRadiance = {depthStencil, GL_DEPTH24_STENCIL8, 16, 16};
    expectError([&] { gi.run(byHand, {}); }, ErrorCode::InvalidArgument, "GBufferView::directRadiance has format");
    byHand.directRadiance = {mono, GL_R16F, 16, 16}; // one channel, where rgb is read (compose refused it)
    expectError([&] { gi.run(byHand, {}); }, ErrorCode::InvalidArgument, "GBufferView::directRadiance has format GL_R16F");
    for (GLuint t : {depthStencil, mipmapped, ids, colour, colourUnorm, mono}) glDeleteTextures(1, &t);
}

TEST_CASE_METHOD(BadInputFixture, "A G-buffer view's normal error outside 0..0.25 is refused", "[bad-input]") {
    AmbientOcclusion ao(ctx);
    ao.run(good, {}); // its shaders and images, made before the count starts
    for (const float error : {-1e-3f, 0.3f, NAN, INFINITY}) {
        GBufferView view = good;
        view.normalError = error;
        expectError([&] { ao.run(view, {}); }, ErrorCode::InvalidArgument, "GBufferView::normalError");
    }
}
