// HostGBuffer::region: a host that renders into part of larger targets hands over the
// rectangle it rendered, and every pass sees exactly what it would have seen had the host
// rendered into textures of that rectangle's size.
#include "gl_fixture.hpp"
#include "obscura/obscura.hpp"
#include "scene_builders.hpp"

#include <catch2/catch.hpp>

#include <algorithm>
#include <climits>
#include <tuple>
#include <string>
#include <vector>

using namespace obscura;

namespace {

constexpr int W = 37, H = 29;              // odd, non-square: the view
constexpr int Pad = 11, PadY = 6;          // the host's targets are (W + Pad) x (H + PadY)
constexpr HostRect kRegion{5, 4, W, H};    // where the view lies in them

// The host's larger targets: every texel set to `fill`, then the view's texels (which our own
// G-buffer rendered at W x H) copied into kRegion. Around the region lie values that would
// change every result near the view's borders, were they read.
struct HostTargets {
    GLuint depth = 0, normal = 0, albedo = 0, radiance = 0, back = 0;

    HostTargets(const GBufferView& view) {
        depth = place(view.depth.name, GL_DEPTH_COMPONENT32F, {0.37f, 0, 0, 0});
        normal = place(view.normal.name, GL_RGBA16F, {0.0f, 0.0f, 1.0f, 1.0f});
        albedo = place(view.albedo.name, GL_SRGB8_ALPHA8, {1.0f, 0.0f, 1.0f, 1.0f});
        radiance = place(view.directRadiance.name, GL_RGBA16F, {50.0f, 50.0f, 50.0f, 1.0f});
        back = place(view.backDepth.name, GL_DEPTH_COMPONENT32F, {0.01f, 0, 0, 0});
    }
    ~HostTargets() {
        for (GLuint t : {depth, normal, albedo, radiance, back}) glDeleteTextures(1, &t);
    }
    HostTargets(const HostTargets&) = delete;
    HostTargets& operator=(const HostTargets&) = delete;

    static GLuint place(GLuint source, GLenum format, glm::vec4 fill) {
        GLuint t = 0;
        glCreateTextures(GL_TEXTURE_2D, 1, &t);
        glTextureStorage2D(t, 1, format, W + Pad, H + PadY);
        const bool isDepth = format == GL_DEPTH_COMPONENT32F;
        glClearTexImage(t, 0, isDepth ? GL_DEPTH_COMPONENT : GL_RGBA, GL_FLOAT, &fill);
        glCopyImageSubData(source, GL_TEXTURE_2D, 0, 0, 0, 0, t, GL_TEXTURE_2D, 0, kRegion.x, kRegion.y, 0, W, H, 1);
        return t;
    }
};

HostGBuffer wholeView(const GBufferView& v, bool all) {
    HostGBuffer in;
    in.depth = v.depth;
    if (!all) return in;
    in.normal = v.normal;
    in.albedo = v.albedo;
    in.directRadiance = v.directRadiance;
    in.backDepth = v.backDepth;
    return in;
}

HostGBuffer regionView(const HostTargets& t, bool all) {
    HostGBuffer in;
    in.depth = {t.depth};
    in.region = kRegion;
    if (!all) return in;
    in.normal = {t.normal};
    in.albedo = {t.albedo};
    in.directRadiance = {t.radiance};
    in.backDepth = {t.back};
    return in;
}

// Identical images, value for value: the copies are bit-exact, and every pass computes a
// pixel from the view's texels and its own coordinates only.
void requireSame(Context& ctx, const TextureView& a, const TextureView& b, const std::string& what) {
    INFO(what);
    REQUIRE(a);
    REQUIRE(b);
    REQUIRE(a.width == W);
    REQUIRE(a.height == H);
    REQUIRE(b.width == W);
    REQUIRE(b.height == H);
    const Image ia = readTexture(ctx, a), ib = readTexture(ctx, b);
    REQUIRE(ia.pixels.size() == ib.pixels.size());
    std::size_t differing = 0;
    for (std::size_t i = 0; i < ia.pixels.size(); ++i)
        if (!(ia.pixels[i] == ib.pixels[i])) ++differing;
    CHECK(differing == 0);
}

// A floor seen from above at `width` x `height`, rendered by `gbuffer`: the host's frame in
// the refusal tests.
const Camera kFloorCamera = Camera::perspective({{0, 1, 3}, {0, 0, 0}, {0, 1, 0}}, 1.0f, float(W) / H, 0.1f, 20.0f);
GBufferView floorView(GBuffer& gbuffer, int width, int height, int depthLayers) {
    GBufferSettings gs{width, height, false, {}};
    gs.depthLayers = depthLayers;
    return gbuffer.render(test::quadScene({{{{{-2, 0, -2}, {-2, 0, 2}, {2, 0, 2}, {2, 0, -2}}}}}), kFloorCamera, gs);
}

} // namespace

TEST_CASE("A host region is adopted as the view of that rectangle", "[gbuffer][host]") {
    test::GlFixture gl;
    Context ctx(gl.desc());
    const Camera camera = Camera::perspective({{1, 2, 4}, {0, 0.5f, 0}, {0, 1, 0}}, 1.0f, float(W) / H, 0.1f, 50.0f,
                                              DepthMode::Reversed);
    const Scene scene = test::cornerScene(true);
    GBuffer ours(ctx), whole(ctx), region(ctx);
    GBufferSettings gs{W, H, true, {}};
    gs.depthLayers = 2;
    const GBufferView rendered = ours.render(scene, camera, gs);
    const HostTargets host(rendered);
    const bool all = GENERATE(false, true); // depth alone (normals from depth), or every buffer
    CAPTURE(all);

    const GBufferView a = whole.adopt(wholeView(rendered, all), camera);
    const GBufferView b = region.adopt(regionView(host, all), camera);
    CHECK(b.width == W);
    CHECK(b.height == H);
    for (const auto& [name, ta, tb] : {std::tuple{"depth", a.depth, b.depth}, std::tuple{"normal", a.normal, b.normal}})
        requireSame(ctx, ta, tb, name);
    if (all)
        for (const auto& [name, ta, tb] : {std::tuple{"albedo", a.albedo, b.albedo},
                                            std::tuple{"direct radiance", a.directRadiance, b.directRadiance},
                                            std::tuple{"back depth", a.backDepth, b.backDepth}})
            requireSame(ctx, ta, tb, name);
    // The copies' memory beside what adopting in place holds (the same normals and frame
    // block), by their formats' sizes: 4 bytes of depth; with every buffer also 8 of RGBA16F
    // normals, 4 of sRGB albedo, 8 of RGBA16F radiance and 4 of back depth.
    CHECK(region.memoryBytes() == whole.memoryBytes() + std::size_t(W) * H * (all ? 28 : 4));

    SECTION("the integrators see the same pixels") {
        AmbientOcclusion aoA(ctx), aoB(ctx);
        AmbientOcclusionSettings s;
        s.radius = 1.5f;
        s.rays = 8;
        s.steps = 8;
        s.bentNormals = true;
        if (all) s.thicknessMode = ScreenThickness::DepthPeeling;
        const AmbientOcclusionView ra = aoA.run(a, s), rb = aoB.run(b, s);
        requireSame(ctx, ra.ao, rb.ao, "ao");
        requireSame(ctx, ra.bentNormal, rb.bentNormal, "bent normal");
        if (all) {
            IndirectLight giA(ctx), giB(ctx);
            IndirectLightSettings g;
            g.radius = 1.5f;
            g.rays = 8;
            g.steps = 8;
            requireSame(ctx, giA.run(a, g).radiance, giB.run(b, g).radiance, "indirect radiance");
        }
    }
    SECTION("the whole texture as a region, or none, is read in place and frees the copies") {
        HostGBuffer in = regionView(host, all);
        in.region = GENERATE(HostRect{0, 0, W + Pad, H + PadY}, HostRect{});
        const GBufferView inPlace = region.adopt(in, camera);
        CHECK(inPlace.depth.name == host.depth);
        CHECK(inPlace.width == W + Pad);
        CHECK(inPlace.height == H + PadY);
        if (all) CHECK(inPlace.albedo.name == host.albedo);
        GBuffer fresh(ctx);
        fresh.adopt(in, camera);
        CHECK(region.memoryBytes() == fresh.memoryBytes());
    }
    SECTION("a copy keeps the host texture's swizzle") {
        const GLint bgra[4] = {GL_BLUE, GL_GREEN, GL_RED, GL_ALPHA};
        glTextureParameteriv(host.depth, GL_TEXTURE_SWIZZLE_RGBA, bgra);
        const GBufferView swizzled = region.adopt(regionView(host, all), camera);
        GLint got[4] = {};
        glGetTextureParameteriv(swizzled.depth.name, GL_TEXTURE_SWIZZLE_RGBA, got);
        CHECK(std::vector<GLint>(got, got + 4) == std::vector<GLint>(bgra, bgra + 4));
    }
    SECTION("what passes sample through a copy is the host's swizzled texel") {
        if (!all) return; // the albedo is what indirect light samples through its swizzle
        IndirectLightSettings g;
        g.radius = 1.5f;
        g.rays = 8;
        g.steps = 8;
        IndirectLight plain(ctx);
        const Image unswizzled = readTexture(ctx, plain.run(a, g).radiance);
        // Green from nothing: the floor's and wall's grey albedo turns magenta.
        const GLint noGreen[4] = {GL_RED, GL_ZERO, GL_BLUE, GL_ALPHA};
        glTextureParameteriv(rendered.albedo.name, GL_TEXTURE_SWIZZLE_RGBA, noGreen);
        glTextureParameteriv(host.albedo, GL_TEXTURE_SWIZZLE_RGBA, noGreen);
        const GBufferView inPlace = whole.adopt(wholeView(rendered, true), camera);
        const GBufferView copied = region.adopt(regionView(host, true), camera);
        IndirectLight giA(ctx), giB(ctx);
        const TextureView ra = giA.run(inPlace, g).radiance, rb = giB.run(copied, g).radiance;
        requireSame(ctx, ra, rb, "indirect radiance, albedo swizzled");
        // The swizzle matters: the light off the albedo had green, and has none through it.
        const Image swizzled = readTexture(ctx, ra);
        REQUIRE(swizzled.channels >= 3);
        REQUIRE(unswizzled.pixels.size() == swizzled.pixels.size());
        std::size_t green = 0, greenLeft = 0;
        for (std::size_t i = 1; i < swizzled.pixels.size(); i += std::size_t(swizzled.channels)) {
            if (unswizzled.pixels[i] > 0.0f) ++green;
            if (swizzled.pixels[i] != 0.0f) ++greenLeft;
        }
        CHECK(green > 0);
        CHECK(greenLeft == 0);
        glTextureParameteri(rendered.albedo.name, GL_TEXTURE_SWIZZLE_G, GL_GREEN);
    }
    CHECK(test::drainGlErrors().empty());
}

TEST_CASE("A host region outside the depth texture is refused before any GL work", "[gbuffer][host][bad-input]") {
    test::GlFixture gl;
    Context ctx(gl.desc());
    GBuffer ours(ctx), adopter(ctx);
    const Camera& camera = kFloorCamera;
    const HostTargets host(floorView(ours, W, H, 2));
    const int tw = W + Pad, th = H + PadY;
    const HostRect bad = GENERATE_COPY(HostRect{-1, 0, 4, 4}, HostRect{0, -1, 4, 4}, HostRect{0, 0, 0, 4},
                                       HostRect{0, 0, 4, 0}, HostRect{0, 0, -3, 4}, HostRect{1, 0, tw, th},
                                       HostRect{0, 1, tw, th}, HostRect{tw, 0, 1, 1}, HostRect{INT_MAX, 0, INT_MAX, 1},
                                       HostRect{0, INT_MAX, 1, INT_MAX}, HostRect{3, 2, 0, 0});
    CAPTURE(bad.x, bad.y, bad.width, bad.height);
    HostGBuffer in = regionView(host, true);
    // A good region first: its copies must outlive the refused call, unchanged.
    const GBufferView good = adopter.adopt(in, camera);
    const std::size_t memory = adopter.memoryBytes();
    in.region = bad;
    try {
        adopter.adopt(in, camera);
        FAIL("adopt accepted the region");
    } catch (const Error& e) {
        CHECK(e.code() == ErrorCode::InvalidArgument);
        CHECK(std::string(e.what()).find("HostGBuffer::region") != std::string::npos);
    }
    CHECK(adopter.memoryBytes() == memory);
    GLint width = 0;
    glGetTextureLevelParameteriv(good.depth.name, 0, GL_TEXTURE_WIDTH, &width);
    CHECK(width == W); // the good region's copy, still there
    CHECK(test::drainGlErrors().empty());
}

TEST_CASE("A view adopt() returned is refused as the same GBuffer's host texture", "[gbuffer][host][bad-input]") {
    test::GlFixture gl;
    Context ctx(gl.desc());
    GBuffer ours(ctx), adopter(ctx), other(ctx);
    const Camera& camera = kFloorCamera;
    const GBufferView rendered = floorView(ours, W, H, 2);
    const HostTargets host(rendered);
    // The region's copies (depth, albedo, radiance, back depth) and the converted normals,
    // all W x H like `rendered`, so that only the ownership check can refuse them.
    const GBufferView returned = adopter.adopt(regionView(host, true), camera);
    const std::size_t memory = adopter.memoryBytes();
    const auto [who, pick] = GENERATE(table<std::string, int>(
        {{"depth", 0}, {"normal", 1}, {"albedo", 2}, {"directRadiance", 3}, {"backDepth", 4}}));
    CAPTURE(who);
    HostGBuffer in;
    in.depth = pick == 0 ? returned.depth : rendered.depth;
    if (pick == 1) in.normal = returned.normal;
    if (pick == 2) in.albedo = returned.albedo;
    if (pick == 3) in.directRadiance = returned.directRadiance;
    if (pick == 4) in.backDepth = returned.backDepth;
    try {
        adopter.adopt(in, camera);
        FAIL("adopt accepted its own view's texture");
    } catch (const Error& e) {
        CHECK(e.code() == ErrorCode::InvalidArgument);
        CHECK_THAT(e.what(), Catch::Contains("HostGBuffer::" + who) && Catch::Contains("is this GBuffer's own output"));
    }
    CHECK(adopter.memoryBytes() == memory);
    GLint width = 0;
    glGetTextureLevelParameteriv(returned.depth.name, 0, GL_TEXTURE_WIDTH, &width);
    CHECK(width == W); // the copy is still there
    // Another GBuffer reads it in place.
    const GBufferView adopted = other.adopt(in, camera);
    CHECK(adopted.width == W);
    CHECK(adopted.depth.name == in.depth.name);
    CHECK(test::drainGlErrors().empty());
}

TEST_CASE("A host region needs textures GL can copy; in place they need not be", "[gbuffer][host][bad-input]") {
    test::GlFixture gl;
    Context ctx(gl.desc());
    GBuffer ours(ctx), adopter(ctx);
    const Camera& camera = kFloorCamera;
    const GBufferView rendered = floorView(ours, W + Pad, H + PadY, 1);
    // A mutable level-0 texture (glTexImage2D) keeps the default min filter,
    // GL_NEAREST_MIPMAP_LINEAR, under which GL counts it incomplete and refuses to copy it.
    GLuint albedo = 0;
    glGenTextures(1, &albedo);
    glBindTexture(GL_TEXTURE_2D, albedo);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, W + Pad, H + PadY, 0, GL_RGBA, GL_UNSIGNED_BYTE, nullptr);
    glBindTexture(GL_TEXTURE_2D, 0);
    HostGBuffer in;
    in.depth = rendered.depth;
    in.albedo = {albedo};
    CHECK(adopter.adopt(in, camera).albedo.name == albedo); // in place: our samplers use no mipmaps
    in.region = kRegion;
    const std::size_t memory = adopter.memoryBytes();
    try {
        adopter.adopt(in, camera);
        FAIL("adopt accepted an incomplete texture to copy");
    } catch (const Error& e) {
        CHECK(e.code() == ErrorCode::InvalidArgument);
        CHECK_THAT(e.what(), Catch::Contains("HostGBuffer::albedo") && Catch::Contains("GL_TEXTURE_MIN_FILTER"));
    }
    CHECK(adopter.memoryBytes() == memory);
    CHECK(test::drainGlErrors().empty());
    glTextureParameteri(albedo, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    const GBufferView copied = adopter.adopt(in, camera);
    CHECK(copied.albedo.name != albedo);
    CHECK(copied.width == W);
    CHECK(test::drainGlErrors().empty());
    glDeleteTextures(1, &albedo);
}

TEST_CASE("A mutable host texture with a mipmap filter is copied where its levels make it complete",
          "[gbuffer][host][bad-input]") {
    test::GlFixture gl;
    Context ctx(gl.desc());
    GBuffer ours(ctx), adopter(ctx);
    const Camera& camera = kFloorCamera;
    // 48 x 20: the sides' log2 differ (5 and 4), so the chain's length comes from the wider
    // side: levels 1-5 are 24x10, 12x5, 6x2, 3x1, 1x1 (the height clamps at 1).
    constexpr int TW = 48, TH = 20;
    constexpr HostRect region{3, 2, 30, 15};
    const GBufferView rendered = floorView(ours, TW, TH, 1);
    enum class Levels { All, MaxLevelZero, MaxLevelTwo, ToSmallerSide, FirstTwo, WrongSize, WrongFormat };
    const Levels levels = GENERATE(Levels::All, Levels::MaxLevelZero, Levels::MaxLevelTwo, Levels::ToSmallerSide,
                                   Levels::FirstTwo, Levels::WrongSize, Levels::WrongFormat);
    const bool complete = levels == Levels::All || levels == Levels::MaxLevelZero || levels == Levels::MaxLevelTwo;
    CAPTURE(int(levels));
    const int last = levels == Levels::FirstTwo        ? 1
                     : levels == Levels::MaxLevelZero  ? 0
                     : levels == Levels::MaxLevelTwo   ? 2
                     : levels == Levels::ToSmallerSide ? 4 // counted from the height: one short
                                                       : 5;
    GLuint albedo = 0;
    glGenTextures(1, &albedo);
    glBindTexture(GL_TEXTURE_2D, albedo);
    for (int i = 0; i <= last; ++i) {
        const GLenum format = levels == Levels::WrongFormat && i == 3 ? GL_RGBA16 : GL_RGBA8;
        const int w = levels == Levels::WrongSize && i == 2 ? 13 : std::max(1, TW >> i);
        const int h = levels == Levels::WrongSize && i == 2 ? 8 : std::max(1, TH >> i);
        glTexImage2D(GL_TEXTURE_2D, i, format, w, h, 0, GL_RGBA, GL_UNSIGNED_BYTE, nullptr);
    }
    if (levels == Levels::MaxLevelZero) glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAX_LEVEL, 0);
    if (levels == Levels::MaxLevelTwo) glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAX_LEVEL, 2);
    glBindTexture(GL_TEXTURE_2D, 0);
    HostGBuffer in;
    in.depth = rendered.depth;
    in.albedo = {albedo};
    in.region = region;
    if (complete) {
        const GBufferView copied = adopter.adopt(in, camera);
        CHECK(copied.albedo.name != albedo);
        CHECK(copied.width == region.width);
    } else {
        CHECK_THROWS_WITH(adopter.adopt(in, camera), Catch::Contains("HostGBuffer::albedo") &&
                                                         Catch::Contains("lacks mipmap levels"));
        CHECK(test::drainGlErrors().empty());
        // GL itself refuses this copy (Mesa since 17.1 checks the mipmap completeness the
        // texture's own min filter asks for): the rule above is GL's, not a stricter one.
        GLuint scratch = 0;
        glCreateTextures(GL_TEXTURE_2D, 1, &scratch);
        glTextureStorage2D(scratch, 1, GL_RGBA8, region.width, region.height);
        glCopyImageSubData(albedo, GL_TEXTURE_2D, 0, region.x, region.y, 0, scratch, GL_TEXTURE_2D, 0, 0, 0, 0,
                           region.width, region.height, 1);
        CHECK(test::drainGlErrors() == std::vector<unsigned>{GL_INVALID_OPERATION});
        glDeleteTextures(1, &scratch);
    }
    CHECK(test::drainGlErrors().empty());
    glDeleteTextures(1, &albedo);
}

TEST_CASE("A host region refuses unsized textures, which GL cannot copy (their storage is the driver's choice)",
          "[gbuffer][host][bad-input]") {
    test::GlFixture gl;
    Context ctx(gl.desc());
    GBuffer ours(ctx), adopter(ctx);
    const Camera& camera = kFloorCamera;
    const GBufferView rendered = floorView(ours, W + Pad, H + PadY, 1);
    const auto [format, needle] = GENERATE(table<GLenum, std::string>(
        {{GL_SRGB_ALPHA, "unsized format (GL_SRGB_ALPHA)"}, {GL_RGBA, "unsized format (GL_RGBA)"}}));
    CAPTURE(needle);
    GLuint albedo = 0;
    glGenTextures(1, &albedo);
    glBindTexture(GL_TEXTURE_2D, albedo);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTexImage2D(GL_TEXTURE_2D, 0, format, W + Pad, H + PadY, 0, GL_RGBA, GL_UNSIGNED_BYTE, nullptr);
    glBindTexture(GL_TEXTURE_2D, 0);
    REQUIRE(test::drainGlErrors().empty());
    HostGBuffer in;
    in.depth = rendered.depth;
    in.albedo = {albedo};
    CHECK(adopter.adopt(in, camera).albedo.name == albedo); // in place, sampled as it is
    in.region = kRegion;
    CHECK_THROWS_WITH(adopter.adopt(in, camera), Catch::Contains("HostGBuffer::albedo") && Catch::Contains(needle));
    CHECK(test::drainGlErrors().empty());
    glDeleteTextures(1, &albedo);
}
