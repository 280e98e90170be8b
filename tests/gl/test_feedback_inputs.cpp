// A module's own output handed back to it as an input (feedback: the last indirect light as
// the next direct radiance, a bent normal as the normal, a drawn texture into itself) would
// be read while the call writes it, which GL leaves undefined. Each call refuses it before
// any GL work and names the input; a second object of the module, which writes elsewhere,
// takes it (drawToHost: another framebuffer).
#include "gl_fixture.hpp"
#include "integrator_settings.hpp"
#include "obscura/obscura.hpp"
#include "scene_builders.hpp"

#include <catch2/catch.hpp>

#include <cmath>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

using namespace obscura;

namespace {

constexpr int W = 24, H = 20;

// The corner under its light: every module has light and occlusion to compute.
struct LitCorner {
    test::GlFixture gl;
    Context ctx{gl.desc()};
    GBuffer gbuffer{ctx};
    Camera camera = Camera::perspective({{1, 2, 4}, {0, 0.5f, 0}, {0, 1, 0}}, 1.0f, float(W) / H, 0.1f, 50.0f);
    GBufferView view;

    LitCorner() { view = gbuffer.render(test::cornerScene(true), camera, {W, H, true, {}}); }
};

// `call` must throw InvalidArgument naming `input` as `module`'s own output, and leave no GL
// error behind.
void requireRefusedAsOwnOutput(const std::function<void()>& call, const std::string& input, const std::string& module) {
    try {
        call();
        FAIL("the call read its own output");
    } catch (const Error& e) {
        CHECK(e.code() == ErrorCode::InvalidArgument);
        CHECK_THAT(e.what(), Catch::Contains(input) && Catch::Contains("is this " + module + "'s own output"));
    }
    CHECK(test::drainGlErrors().empty());
}

// Every texel finite: what the second object computed from the fed-back texture.
void requireFinite(Context& ctx, const TextureView& texture) {
    const Image image = readTexture(ctx, texture);
    REQUIRE_FALSE(image.pixels.empty());
    std::size_t bad = 0;
    for (const float v : image.pixels)
        if (!std::isfinite(v)) ++bad;
    CHECK(bad == 0);
}

} // namespace

TEST_CASE("Indirect light refuses its own last radiance as direct radiance; a second object takes it",
          "[gi][bad-input]") {
    LitCorner f;
    IndirectLight gi(f.ctx), other(f.ctx);
    // At half resolution the output is another texture.
    auto s = test::integratorSettings<IndirectLightSettings>(1.5f, 4, 4, GENERATE(AoResolution::Full, AoResolution::Half));
    CAPTURE(int(s.resolution));
    const IndirectLightView first = gi.run(f.view, s);
    const std::size_t memory = gi.memoryBytes();
    GBufferView fed = f.view;
    fed.directRadiance = first.radiance;
    requireRefusedAsOwnOutput([&] { gi.run(fed, s); }, "GBufferView::directRadiance", "IndirectLight");
    GBufferView asAlbedo = f.view;
    asAlbedo.albedo = first.radiance;
    requireRefusedAsOwnOutput([&] { gi.run(asAlbedo, s); }, "GBufferView::albedo", "IndirectLight");
    CHECK(gi.memoryBytes() == memory);
    // Two objects alternate: the second bounce reads the first's light.
    requireFinite(f.ctx, other.run(fed, s).radiance);
    CHECK(test::drainGlErrors().empty());
}

TEST_CASE("Ambient occlusion refuses its own bent normals as the normal; a second object takes them",
          "[ao][bad-input]") {
    LitCorner f;
    AmbientOcclusion ao(f.ctx), other(f.ctx);
    auto s = test::integratorSettings<AmbientOcclusionSettings>(1.0f, 4, 4, GENERATE(AoResolution::Full, AoResolution::Half));
    s.bentNormals = true;
    CAPTURE(int(s.resolution));
    const AmbientOcclusionView first = ao.run(f.view, s);
    REQUIRE(first.bentNormal);
    const std::size_t memory = ao.memoryBytes();
    GBufferView fed = f.view;
    fed.normal = first.bentNormal;
    requireRefusedAsOwnOutput([&] { ao.run(fed, s); }, "GBufferView::normal", "AmbientOcclusion");
    CHECK(ao.memoryBytes() == memory);
    if (s.resolution == AoResolution::Half) { // a full-resolution run leaves the half one's output alone
        AmbientOcclusionSettings full = s;
        full.resolution = AoResolution::Full;
        requireFinite(f.ctx, ao.run(fed, full).ao);
    }
    requireFinite(f.ctx, other.run(fed, s).ao);
    CHECK(test::drainGlErrors().empty());
}

TEST_CASE("The composer refuses its own radiance as an input; a second composer takes it", "[compose][bad-input]") {
    LitCorner f;
    Composer composer(f.ctx), other(f.ctx);
    const ComposeSettings s;
    ComposeInputs in;
    in.gbuffer = f.view;
    composer.compose(in, s);
    const std::size_t memory = composer.memoryBytes();
    ComposeInputs asDirect = in;
    asDirect.gbuffer.directRadiance = composer.radiance();
    requireRefusedAsOwnOutput([&] { composer.compose(asDirect, s); }, "GBufferView::directRadiance", "Composer");
    ComposeInputs asIndirect = in;
    asIndirect.indirect = composer.radiance();
    requireRefusedAsOwnOutput([&] { composer.compose(asIndirect, s); }, "ComposeInputs::indirect", "Composer");
    ComposeInputs displayAsAlbedo = in; // the tone-mapped image is compose()'s result
    displayAsAlbedo.gbuffer.albedo = composer.compose(in, s);
    requireRefusedAsOwnOutput([&] { composer.compose(displayAsAlbedo, s); }, "GBufferView::albedo", "Composer");
    CHECK(composer.memoryBytes() == memory);
    requireFinite(f.ctx, other.compose(asIndirect, s));
    CHECK(test::drainGlErrors().empty());
}

TEST_CASE("The G-buffer refuses its own image as a material texture; a second G-buffer takes it", "[gbuffer][bad-input]") {
    LitCorner f;
    // Last frame's lit image on a screen in the scene: render() would draw into the texture
    // it samples.
    Scene scene = test::cornerScene(true);
    scene.materials[0].albedoTexture = f.view.directRadiance.name;
    requireRefusedAsOwnOutput([&] { f.gbuffer.render(scene, f.camera, {W, H, true, {}}); },
                              "Scene::materials[0].albedoTexture", "GBuffer");
    GBuffer other(f.ctx);
    requireFinite(f.ctx, other.render(scene, f.camera, {W, H, true, {}}).directRadiance);
    CHECK(test::drainGlErrors().empty());
}

TEST_CASE("drawToHost refuses a framebuffer with the source's level 0 at any colour attachment",
          "[compose][host][bad-input]") {
    LitCorner f;
    Composer composer(f.ctx);
    GLuint source = 0, elsewhere = 0, buffer = 0, fbo = 0;
    glCreateTextures(GL_TEXTURE_2D, 1, &source);
    glTextureStorage2D(source, 2, GL_RGBA8, W, H); // level 1 may be drawn into: it is not sampled
    glCreateTextures(GL_TEXTURE_2D, 1, &elsewhere);
    glTextureStorage2D(elsewhere, 1, GL_RGBA8, W, H);
    glCreateRenderbuffers(1, &buffer);
    glNamedRenderbufferStorage(buffer, GL_RGBA8, W, H);
    const glm::vec4 grey(0.25f, 0.5f, 0.75f, 1.0f);
    glClearTexImage(source, 0, GL_RGBA, GL_FLOAT, &grey);
    const TextureView view{source, GL_RGBA8, W, H};
    const HostTarget target{0, 0, 0, W, H, HostBlend::Overwrite, HostSourceEncoding::Display};
    const auto drawInto = [&](GLuint framebuffer) {
        HostTarget t = target;
        t.framebuffer = framebuffer;
        composer.drawToHost(view, t);
    };
    enum class Attached { SourceFirst, SourceSecond, SourceLevelOne, Renderbuffer };
    const Attached attached = GENERATE(Attached::SourceFirst, Attached::SourceSecond, Attached::SourceLevelOne, Attached::Renderbuffer);
    CAPTURE(int(attached));
    glCreateFramebuffers(1, &fbo);
    if (attached == Attached::SourceFirst) glNamedFramebufferTexture(fbo, GL_COLOR_ATTACHMENT0, source, 0);
    if (attached == Attached::SourceSecond) { // not a draw buffer: GL still calls it a loop
        glNamedFramebufferTexture(fbo, GL_COLOR_ATTACHMENT0, elsewhere, 0);
        glNamedFramebufferTexture(fbo, GL_COLOR_ATTACHMENT1, source, 0);
    }
    if (attached == Attached::SourceLevelOne) glNamedFramebufferTexture(fbo, GL_COLOR_ATTACHMENT0, source, 1);
    if (attached == Attached::Renderbuffer) glNamedFramebufferRenderbuffer(fbo, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, buffer);
    REQUIRE(glCheckNamedFramebufferStatus(fbo, GL_DRAW_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE);
    if (attached == Attached::SourceFirst || attached == Attached::SourceSecond) {
        const std::string at = attached == Attached::SourceFirst ? "GL_COLOR_ATTACHMENT0" : "GL_COLOR_ATTACHMENT1";
        CHECK_THROWS_WITH(drawInto(fbo), Catch::Contains("level 0 of the source texture") && Catch::Contains(at) &&
                                             Catch::Contains("feedback loop"));
    } else {
        CHECK_NOTHROW(drawInto(fbo));
        // Level 1 now holds the source's values: 0.5 in 8 bits is 127 or 128 (one step either way).
        if (attached == Attached::SourceLevelOne) {
            std::vector<std::uint8_t> texel(std::size_t(W / 2) * (H / 2) * 4);
            glGetTextureImage(source, 1, GL_RGBA, GL_UNSIGNED_BYTE, GLsizei(texel.size()), texel.data());
            CHECK(int(texel[1]) == Approx(0.5 * 255).margin(1));
        }
    }
    CHECK(test::drainGlErrors().empty());
    // Into a framebuffer without it, it is drawn: the value arrives.
    GLuint other = 0;
    glCreateFramebuffers(1, &other);
    glNamedFramebufferTexture(other, GL_COLOR_ATTACHMENT0, elsewhere, 0);
    drawInto(other);
    const Image drawn = readTexture(f.ctx, {elsewhere, GL_RGBA8, W, H});
    REQUIRE(drawn.channels == 4);
    CHECK(drawn.pixels[1] == Approx(0.5f).margin(1.0 / 255));
    CHECK(test::drainGlErrors().empty());
    glDeleteFramebuffers(1, &fbo);
    glDeleteFramebuffers(1, &other);
    glDeleteRenderbuffers(1, &buffer);
    glDeleteTextures(1, &source);
    glDeleteTextures(1, &elsewhere);
}
