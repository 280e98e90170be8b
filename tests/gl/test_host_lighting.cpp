// Post-process mode with the host's albedo and lit image: indirect light and the final
// combine run on adopted host buffers and compute what they compute on Obscura's G-buffer,
// a lit open plane gives no indirect light through coarse host normals, and poisoned host
// buffers (NaN, Inf, zero, out of range) give finite outputs in range.
#include "ao_fixture.hpp"
#include "scene_builders.hpp"

#include "obscura/assets.hpp"

#include <catch2/catch.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <utility>
#include <vector>

using namespace obscura;

namespace {

// A new host texture of `format` holding `source`'s level 0, copied texel for texel (the
// formats must be copy-compatible) or, for a wider float format, converted exactly through
// a float read-back. The caller deletes it.
GLuint hostCopy(Context& ctx, const TextureView& source, GLenum format) {
    GLuint texture = 0;
    glCreateTextures(GL_TEXTURE_2D, 1, &texture);
    glTextureStorage2D(texture, 1, format, source.width, source.height);
    if (format == source.internalFormat) {
        glCopyImageSubData(source.name, GL_TEXTURE_2D, 0, 0, 0, 0, texture, GL_TEXTURE_2D, 0, 0, 0, 0, source.width,
                           source.height, 1);
        return texture;
    }
    const Image image = readTexture(ctx, source); // row 0 at the top; GL's row 0 is the bottom
    std::vector<float> rows(image.pixels.size());
    const std::size_t row = std::size_t(image.width) * image.channels;
    for (int y = 0; y < image.height; ++y)
        std::copy_n(image.pixels.begin() + std::ptrdiff_t(row * std::size_t(image.height - 1 - y)), row,
                    rows.begin() + std::ptrdiff_t(row * std::size_t(y)));
    const GLenum layout = image.channels == 4 ? GL_RGBA : GL_RGB;
    glTextureSubImage2D(texture, 0, 0, 0, source.width, source.height, layout, GL_FLOAT, rows.data());
    return texture;
}

} // namespace

TEST_CASE("Post-process mode: with the host's albedo and lit image, indirect light and compose give the G-buffer "
          "path's result bit for bit", "[gi][compose][host]") {
    // The host's textures hold the same values as Obscura's (its depth pass writes 32-bit float
    // depth exactly, the albedo is the same sRGB bytes, the radiance the same half floats, or
    // those widened to 32-bit floats, which is exact); so every method and resolution must
    // give the same numbers on the adopted buffers as on the G-buffer.
    test::AoFixture f;
    const assets::LoadedScene cornell = assets::builtinScene("cornell");
    constexpr int W = 48, H = 40;
    const Camera camera = test::cornellCamera(W, H);
    f.view = f.gbuffer.render(cornell.scene, camera, {W, H, true, {}}); // lit by the scene's lights
    IndirectLight gi(f.ctx);
    Composer composer(f.ctx);
    const GLuint depth = test::copyDepthAsHost(f.view.depth.name, W, H, GL_DEPTH_COMPONENT32F);
    const GLuint albedo = hostCopy(f.ctx, f.view.albedo, GL_SRGB8_ALPHA8);
    for (const GLenum radianceFormat : {GLenum(GL_RGBA16F), GLenum(GL_RGBA32F)}) {
        CAPTURE(radianceFormat);
        const GLuint radiance = hostCopy(f.ctx, f.view.directRadiance, radianceFormat);
        HostGBuffer host;
        host.depth = {depth, GL_DEPTH_COMPONENT32F, W, H};
        host.normal = f.view.normal;
        host.albedo = {albedo, 0, 0, 0}; // a name is enough: adopt describes it as GL reports it
        host.directRadiance = {radiance, radianceFormat, W, H};
        GBuffer adopter(f.ctx);
        GBufferView adopted = adopter.adopt(host, camera);
        adopted.normalError = f.view.normalError; // the G-buffer's normals, rounded once (adoptedNormalError)
        CHECK(adopted.albedo.name == albedo); // read in place
        CHECK(adopted.albedo.internalFormat == GL_SRGB8_ALPHA8);
        CHECK(adopted.albedo.width == W);
        CHECK(adopted.directRadiance.name == radiance);
        const VoxelGrid& voxels = f.voxelizer.voxelize(cornell.scene, {});
        for (const GiMethod method : {GiMethod::Screen, GiMethod::Hybrid})
            for (const AoResolution resolution : {AoResolution::Full, AoResolution::Half}) {
                CAPTURE(static_cast<int>(method), static_cast<int>(resolution));
                IndirectLightSettings s;
                s.method = method;
                s.radius = 300.0f;
                s.rays = 16;
                s.resolution = resolution;
                s.blurRadius = resolution == AoResolution::Full ? 0 : 2;
                if (method == GiMethod::Hybrid) s.voxels = &voxels;
                const IndirectLightView ownView = gi.run(f.view, s);
                const Image own = readTexture(f.ctx, ownView.radiance);
                const TextureView ownComposed = composer.compose({f.view, {}, ownView.radiance}, {});
                const Image ownImage = readTexture(f.ctx, ownComposed);
                const IndirectLightView postView = gi.run(adopted, s);
                const Image post = readTexture(f.ctx, postView.radiance);
                int lit = 0;
                for (std::size_t i = 0; i < own.pixels.size(); i += 4) lit += own.pixels[i] > 0.0f;
                CHECK(lit > W * H / 4); // nothing gathered would prove nothing
                CHECK(post.pixels == own.pixels);
                CHECK(readTexture(f.ctx, composer.compose({adopted, {}, postView.radiance}, {})).pixels == ownImage.pixels);
            }
        glDeleteTextures(1, &radiance);
    }
    glDeleteTextures(1, &albedo);
    glDeleteTextures(1, &depth);
    CHECK(test::drainGlErrors().empty());
}

TEST_CASE("Post-process mode: on a host's 8-, 10- and 16-bit normals a lit open plane gives exactly no indirect "
          "light", "[gi][host]") {
    // Every ray leaves the plane into the empty sky, so E_ind = 0 exactly. The host's encoding
    // tilts the stored tangent plane by up to GBufferView::normalError (adoptedNormalError); a
    // ray that the screen test then found under the plane would bring the plane's own light
    // back. Screen GI with each march and hybrid GI, full and half resolution, view- and
    // world-space normals; perspective, and the grazing orthographic view of the AO test.
    // Measured: this passes with the G-buffer's own 2^-10 in normalError's place too, since
    // GI also reads a hit only through a face the ray enters (giScreenRadiance), which a ray
    // leaving the plane does not; so it guards the result, not the margin (the AO test does).
    test::AoFixture f;
    const Scene scene = test::withSun(test::floorScene());
    constexpr int W = 64, H = 48;
    const Camera cameras[] = {
        Camera::perspective({{0, 3, 6}, {0, 0, 0}, {0, 1, 0}}, glm::radians(50.0f), float(W) / H, 0.05f, 200.0f),
        Camera::orthographic({{1, 1.5f, 5}, {0, 0, 0}, {0, 1, 0}}, 4.8f, float(W) / H, 0.05f, 100.0f)};
    IndirectLight gi(f.ctx);
    VoxelizerSettings grid;
    grid.resolution = 64;
    const VoxelGrid& voxels = f.voxelizer.voxelize(scene, grid);
    struct Variant {
        GiMethod method;
        ScreenMarch march;
    };
    for (int c = 0; c < 2; ++c) {
        const Camera& camera = cameras[c];
        f.view = f.gbuffer.render(scene, camera, {W, H, true, {}});
        const Image normals = readTexture(f.ctx, f.view.normal);
        const Image direct = readTexture(f.ctx, f.view.directRadiance);
        int lit = 0;
        for (std::size_t i = 0; i < direct.pixels.size(); i += 4) lit += direct.pixels[i] > 0.0f;
        CHECK(lit > W * H / 2); // there is light to leak
        const GLuint depth = test::copyDepthAsHost(f.view.depth.name, W, H, GL_DEPTH_COMPONENT32F);
        for (const GLenum format : {GL_RGBA8, GL_RGB10_A2, GL_RGBA16})
            for (const NormalSpace space : {NormalSpace::View, NormalSpace::World}) {
                const GLuint normal = test::hostNormalTexture(normals, camera, format, space);
                HostGBuffer host = test::unsignedNormalHost(depth, normal, format, space, W, H);
                host.albedo = f.view.albedo;
                host.directRadiance = f.view.directRadiance;
                GBuffer adopter(f.ctx);
                const GBufferView adopted = adopter.adopt(host, camera);
                for (const Variant variant : {Variant{GiMethod::Screen, ScreenMarch::View}, Variant{GiMethod::Screen, ScreenMarch::Texture},
                                              Variant{GiMethod::Screen, ScreenMarch::HiZ}, Variant{GiMethod::Hybrid, ScreenMarch::View}})
                    for (const AoResolution resolution : {AoResolution::Full, AoResolution::Half}) {
                        CAPTURE(c, format, static_cast<int>(space), static_cast<int>(variant.method),
                                static_cast<int>(variant.march), static_cast<int>(resolution));
                        IndirectLightSettings s;
                        s.method = variant.method;
                        s.march = variant.march;
                        s.radius = 2.0f;
                        s.rays = 24;
                        s.resolution = resolution;
                        s.blurRadius = resolution == AoResolution::Full ? 0 : 2;
                        if (variant.method == GiMethod::Hybrid) s.voxels = &voxels;
                        const Image radiance = readTexture(f.ctx, gi.run(adopted, s).radiance);
                        REQUIRE(radiance.channels == 4);
                        std::size_t notZero = 0; // rgb: alpha is not light
                        for (std::size_t i = 0; i < radiance.pixels.size(); ++i)
                            notZero += i % 4 != 3 && radiance.pixels[i] != 0.0f;
                        CHECK(notZero == 0);
                    }
                glDeleteTextures(1, &normal);
            }
        glDeleteTextures(1, &depth);
    }
    CHECK(test::drainGlErrors().empty());
}

namespace {

// What a host's float buffers may hold where its own passes went wrong, one pattern a pixel
// in turn (pixels whose index is 0 mod 9 keep their value).
glm::vec3 poisonOf(std::size_t pixel, glm::vec3 value) {
    const float nan = std::nanf(""), inf = INFINITY;
    switch (pixel % 9) {
    case 1: return {nan, value.y, value.z};
    case 2: return glm::vec3(inf);
    case 3: return {-inf, value.y, inf};
    case 4: return glm::vec3(0.0f);
    case 5: return glm::vec3(1e-40f);   // subnormal
    case 6: return glm::vec3(3e38f);    // overflows any sum of squares
    case 7: return -value;              // a normal facing away, a negative colour
    case 8: return value * 1e6f;
    }
    return value;
}

// `image` (row 0 at the top) poisoned by poisonOf, as a new GL_RGBA32F host texture.
GLuint poisonedTexture(const Image& image) { return test::hostRgbTexture(image, GL_RGBA32F, poisonOf); }

// Non-finite values, and values outside [lo, hi], in an image's first `channels` channels.
std::size_t outsideCount(const Image& image, int channels, float lo, float hi) {
    std::size_t n = 0;
    for (std::size_t i = 0; i < image.pixels.size(); ++i) {
        const float v = image.pixels[i];
        if (int(i % std::size_t(image.channels)) < channels) n += !(std::isfinite(v) && v >= lo && v <= hi);
    }
    return n;
}

// The poisoned-buffer tests' integrator settings on the Cornell box: 16 rays of 300 units
// (half the box), the voxel methods on `voxels`, bent normals on.
AmbientOcclusionSettings poisonedAoSettings(AoMethod method, AoResolution resolution, int blur, const VoxelGrid& voxels) {
    AmbientOcclusionSettings s;
    s.method = method;
    s.radius = 300.0f;
    s.rays = 16;
    s.resolution = resolution;
    s.blurRadius = blur;
    s.bentNormals = true;
    if (method == AoMethod::Voxel) s.voxels = &voxels;
    return s;
}

IndirectLightSettings poisonedGiSettings(GiMethod method, AoResolution resolution, int blur, const VoxelGrid& voxels) {
    IndirectLightSettings s;
    s.method = method;
    s.radius = 300.0f;
    s.rays = 16;
    s.resolution = resolution;
    s.blurRadius = blur;
    if (method == GiMethod::Hybrid) s.voxels = &voxels;
    return s;
}

} // namespace

TEST_CASE("Post-process mode: NaN, Inf, zero and out-of-range host normals, albedo and radiance give finite AO, "
          "bent normals, indirect light and display values", "[ao][gi][compose][host][stability]") {
    // A host's float buffers are not ours to trust: every pixel of the Cornell box view holds
    // one of poisonOf's patterns in its normal, albedo and lit image. Outputs must stay finite
    // and in their ranges: AO in [0, 1], bent normals unit, indirect light in [0, 65504],
    // display values in [0, 1].
    test::AoFixture f;
    const assets::LoadedScene cornell = assets::builtinScene("cornell");
    constexpr int W = 48, H = 40;
    const Camera camera = test::cornellCamera(W, H);
    f.view = f.gbuffer.render(cornell.scene, camera, {W, H, true, {}});
    f.positions = readTexture(f.ctx, f.gbuffer.positions(f.view));
    const GLuint depth = test::copyDepthAsHost(f.view.depth.name, W, H, GL_DEPTH_COMPONENT32F);
    const GLuint normal = poisonedTexture(readTexture(f.ctx, f.view.normal));
    const GLuint albedo = poisonedTexture(readTexture(f.ctx, f.view.albedo));
    const GLuint radiance = poisonedTexture(readTexture(f.ctx, f.view.directRadiance));
    HostGBuffer host;
    host.depth = {depth, GL_DEPTH_COMPONENT32F, W, H};
    host.normal = {normal, GL_RGBA32F, W, H};
    host.albedo = {albedo, GL_RGBA32F, W, H};
    host.directRadiance = {radiance, GL_RGBA32F, W, H};
    GBuffer adopter(f.ctx);
    const GBufferView adopted = adopter.adopt(host, camera);
    CHECK(outsideCount(readTexture(f.ctx, adopted.normal), 3, -1.0f, 1.0f) == 0);
    const VoxelGrid& voxels = f.voxelizer.voxelize(cornell.scene, {});
    IndirectLight gi(f.ctx);
    Composer composer(f.ctx);
    // Full resolution with and without the blur, half with it: each place the albedo is
    // multiplied in (the integrator, the blur's last pass, the upsampling).
    for (const auto& [resolution, blur] : {std::pair{AoResolution::Full, 0}, std::pair{AoResolution::Full, 2},
                                           std::pair{AoResolution::Half, 2}}) {
        CAPTURE(static_cast<int>(resolution), blur);
        TextureView aoTexture;
        for (const AoMethod method : {AoMethod::RayMarch, AoMethod::Points, AoMethod::Horizon, AoMethod::Voxel}) {
            CAPTURE(static_cast<int>(method));
            const AmbientOcclusionView out = f.ao.run(adopted, poisonedAoSettings(method, resolution, blur, voxels));
            CHECK(outsideCount(readTexture(f.ctx, out.ao), 1, 0.0f, 1.0f) == 0);
            const Image bent = readTexture(f.ctx, out.bentNormal);
            CHECK(outsideCount(bent, 3, -1.0f, 1.0f) == 0);
            // Unit where there is geometry: stored as half floats, within 2^-10 (kHalfNormalError).
            std::size_t notUnit = 0, geometry = 0;
            for (int y = 0; y < H; ++y)
                for (int x = 0; x < W; ++x) {
                    if (!f.geometry(x, y)) continue;
                    ++geometry;
                    const glm::dvec3 b(bent.at(x, y, 0), bent.at(x, y, 1), bent.at(x, y, 2));
                    notUnit += !(std::abs(glm::length(b) - 1.0) <= kHalfNormalError + 1e-6);
                }
            CHECK(geometry > std::size_t(W * H / 2));
            CHECK(notUnit == 0);
            aoTexture = out.ao;
        }
        for (const GiMethod method : {GiMethod::Screen, GiMethod::Hybrid}) {
            CAPTURE(static_cast<int>(method));
            const IndirectLightSettings s = poisonedGiSettings(method, resolution, blur, voxels);
            const TextureView indirect = gi.run(adopted, s).radiance;
            const Image first = readTexture(f.ctx, indirect);
            CHECK(outsideCount(first, 3, 0.0f, 65504.0f) == 0);
            // The same again: here more pixels ask for refinement than its list holds, and
            // which of them got in depended on the GPU's order (39 of 40 reruns differed at
            // half resolution) until an overflowing list refined none.
            CHECK(readTexture(f.ctx, gi.run(adopted, s).radiance).pixels == first.pixels);
            for (const CombineFormula formula : {CombineFormula::Standard, CombineFormula::Thesis, CombineFormula::Physical})
                for (const ToneMapper mapper : {ToneMapper::None, ToneMapper::Drago, ToneMapper::Aces}) {
                    CAPTURE(static_cast<int>(formula), static_cast<int>(mapper));
                    ComposeSettings c;
                    c.formula = formula;
                    c.toneMapper = mapper;
                    c.ambient = glm::vec3(0.5f);
                    const TextureView display = composer.compose({adopted, aoTexture, indirect}, c);
                    CHECK(outsideCount(readTexture(f.ctx, composer.radiance()), 3, 0.0f, 65504.0f) == 0);
                    CHECK(outsideCount(readTexture(f.ctx, display), 3, 0.0f, 1.0f) == 0);
                }
        }
    }
    for (const GLuint t : {depth, normal, albedo, radiance}) glDeleteTextures(1, &t);
    CHECK(test::drainGlErrors().empty());
}

namespace {

// Depth values a host's GL_DEPTH_COMPONENT32F texture may hold (ARB_depth_buffer_float keeps
// uploaded float depth unclamped), and for which camera each is background
// (isBackgroundDepth): NaN of both signs, +-Inf, values below 0 and above 1 (the float just
// above 1 too), the largest floats, whatever the camera; -0.0 and subnormals of both signs,
// which count as 0: the clear depth with reversed-Z, the near plane otherwise; the smallest
// normal float and 1e-30, farther than kMaxViewDistance with reversed-Z and an infinite far
// plane (view z = -near / d), just in front of the far plane with a finite one.
enum class PoisonBackground { Always, Reversed, InfiniteFar };
struct DepthPoison {
    float value;
    PoisonBackground when;
};
const std::vector<DepthPoison> kDepthPoisons = {
    {std::nanf(""), PoisonBackground::Always},           {-std::nanf(""), PoisonBackground::Always},
    {INFINITY, PoisonBackground::Always},                {-INFINITY, PoisonBackground::Always},
    {-0.25f, PoisonBackground::Always},                  {1.25f, PoisonBackground::Always},
    {std::nextafter(1.0f, 2.0f), PoisonBackground::Always}, {3e38f, PoisonBackground::Always},
    {-3e38f, PoisonBackground::Always},                  {-0.0f, PoisonBackground::Reversed},
    {1e-40f, PoisonBackground::Reversed},                {-1e-40f, PoisonBackground::Reversed},
    {std::numeric_limits<float>::min(), PoisonBackground::InfiniteFar}, {1e-30f, PoisonBackground::InfiniteFar}};

// The poisoned pixels: the centre of every 3 x 3 block, so that rays, blur taps and the
// upsampling meet them everywhere, while every other pixel keeps a neighbour on each side
// for normals reconstructed from depth. -1 where the depth is kept.
int poisonIndex(int x, int y) {
    return x % 3 == 1 && y % 3 == 1 ? (x / 3 + 7 * (y / 3)) % int(kDepthPoisons.size()) : -1;
}

std::vector<float> depthTexels(GLuint texture, int width, int height) {
    std::vector<float> texels(std::size_t(width) * height);
    glGetTextureImage(texture, 0, GL_DEPTH_COMPONENT, GL_FLOAT, GLsizei(texels.size() * sizeof(float)), texels.data());
    return texels;
}

// Writes texels[i] into the pixels marked in `where` (GL rows). Uploads clamp depth to
// [0, 1] (Mesa's do, NaN to 0), and so does a scissored clear, which Mesa draws as a quad at
// the clear depth (clipped away outside [0, 1]); a whole clear of a float depth attachment
// is not clamped (glClearBufferfv, GL 4.5 section 17.4.3.1), and glCopyImageSubData copies
// texels as they are: a 1 x 1 texture cleared to each value, copied into its pixel.
void poisonDepth(GLuint depth, int width, int height, const std::vector<float>& texels, const std::vector<char>& where) {
    GLuint texel = 0, framebuffer = 0;
    glCreateTextures(GL_TEXTURE_2D, 1, &texel);
    glTextureStorage2D(texel, 1, GL_DEPTH_COMPONENT32F, 1, 1);
    glCreateFramebuffers(1, &framebuffer);
    glNamedFramebufferTexture(framebuffer, GL_DEPTH_ATTACHMENT, texel, 0);
    REQUIRE(glCheckNamedFramebufferStatus(framebuffer, GL_DRAW_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE);
    glDepthMask(GL_TRUE);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            const std::size_t i = std::size_t(y) * width + x;
            if (!where[i]) continue;
            glClearNamedFramebufferfv(framebuffer, GL_DEPTH, 0, &texels[i]);
            glCopyImageSubData(texel, GL_TEXTURE_2D, 0, 0, 0, 0, depth, GL_TEXTURE_2D, 0, x, y, 0, 1, 1, 1);
        }
    glDeleteFramebuffers(1, &framebuffer);
    glDeleteTextures(1, &texel);
}

std::uint32_t bitsOf(float v) {
    std::uint32_t bits;
    std::memcpy(&bits, &v, sizeof bits);
    return bits;
}

} // namespace

TEST_CASE("Post-process mode: host depth holding NaN, Inf or values outside 0..1 is background to every pass, and "
          "every output stays finite", "[ao][gi][compose][host][stability]") {
    // Such a pixel stands for no surface. Each pass must treat it as the background: AO 1 and
    // no bent normal, no indirect light, the direct radiance alone after compose, alpha 0 in
    // the positions and reconstructed normals; and its neighbours, whose rays, blur taps and
    // upsampling read it, must stay finite and in range. Standard depth, reversed-Z and
    // reversed-Z with an infinite far plane, each with the host's normals and with normals
    // reconstructed from the poisoned depth.
    test::AoFixture f;
    const assets::LoadedScene cornell = assets::builtinScene("cornell");
    const VoxelGrid& voxels = f.voxelizer.voxelize(cornell.scene, {});
    constexpr int W = 48, H = 40;
    IndirectLight gi(f.ctx);
    Composer composer(f.ctx);
    GBuffer adopter(f.ctx);
    for (const PoisonBackground mode : {PoisonBackground::Always, PoisonBackground::Reversed, PoisonBackground::InfiniteFar}) {
        const bool reversed = mode != PoisonBackground::Always, infinite = mode == PoisonBackground::InfiniteFar;
        CAPTURE(reversed, infinite);
        const Camera camera = Camera::perspective({{278, 273, -700}, {278, 273, 0}, {0, 1, 0}}, glm::radians(40.0f),
                                                  float(W) / float(H), 10.0f, infinite ? INFINITY : 5000.0f,
                                                  reversed ? DepthMode::Reversed : DepthMode::Standard);
        f.view = f.gbuffer.render(cornell.scene, camera, {W, H, true, {}});
        const GLuint depth = test::copyDepthAsHost(f.view.depth.name, W, H, GL_DEPTH_COMPONENT32F);
        std::vector<float> texels = depthTexels(depth, W, H); // GL rows: y = 0 at the bottom
        std::vector<char> background(texels.size()), poisoned(texels.size());
        for (int y = 0; y < H; ++y)
            for (int x = 0; x < W; ++x) {
                const std::size_t i = std::size_t(y) * W + x;
                const int k = poisonIndex(x, y);
                poisoned[i] = k >= 0;
                const DepthPoison* poison = k >= 0 ? &kDepthPoisons[std::size_t(k)] : nullptr;
                if (poison) texels[i] = poison->value;
                background[i] = poison ? poison->when <= mode : texels[i] == (reversed ? 0.0f : 1.0f);
            }
        poisonDepth(depth, W, H, texels, poisoned);
        // The premise: the texture holds the poisons as given (NaNs may lose their payload).
        const std::vector<float> stored = depthTexels(depth, W, H);
        std::size_t changed = 0;
        for (std::size_t i = 0; i < texels.size(); ++i)
            changed += std::isnan(texels[i]) ? !std::isnan(stored[i]) : bitsOf(stored[i]) != bitsOf(texels[i]);
        REQUIRE(changed == 0);
        // readTexture's row 0 is the top.
        const auto at = [&](const std::vector<char>& mask, int x, int yTop) { return mask[std::size_t(H - 1 - yTop) * W + x] != 0; };
        for (const bool hostNormals : {true, false}) {
            CAPTURE(hostNormals);
            HostGBuffer host;
            host.depth = {depth, GL_DEPTH_COMPONENT32F, W, H};
            if (hostNormals) host.normal = f.view.normal;
            host.albedo = f.view.albedo;
            host.directRadiance = f.view.directRadiance;
            const GBufferView adopted = adopter.adopt(host, camera);
            const Image positions = readTexture(f.ctx, adopter.positions(adopted));
            const Image normals = readTexture(f.ctx, adopted.normal);
            std::size_t wrongPositions = 0, wrongNormals = 0, surfaces = 0;
            for (int y = 0; y < H; ++y)
                for (int x = 0; x < W; ++x) {
                    const bool sky = at(background, x, y);
                    surfaces += !sky;
                    wrongPositions += (positions.at(x, y, 3) == 0.0f) != sky;
                    if (sky) wrongNormals += normals.at(x, y, 3) != 0.0f;
                }
            CHECK(surfaces > std::size_t(W * H / 2));
            CHECK(wrongPositions == 0);
            CHECK(wrongNormals == 0);
            CHECK(outsideCount(positions, 4, -1e4f, 1e4f) == 0); // the box is 560 units across, 700 away
            CHECK(outsideCount(normals, 3, -1.0f, 1.0f) == 0);
            for (const auto& [resolution, blur] : {std::pair{AoResolution::Full, 0}, std::pair{AoResolution::Half, 2}}) {
                CAPTURE(static_cast<int>(resolution), blur);
                TextureView aoTexture;
                for (const AoMethod method : {AoMethod::RayMarch, AoMethod::Points, AoMethod::Horizon, AoMethod::Voxel}) {
                    CAPTURE(static_cast<int>(method));
                    const AmbientOcclusionView out = f.ao.run(adopted, poisonedAoSettings(method, resolution, blur, voxels));
                    const Image ao = readTexture(f.ctx, out.ao), bent = readTexture(f.ctx, out.bentNormal);
                    CHECK(outsideCount(ao, 1, 0.0f, 1.0f) == 0);
                    CHECK(outsideCount(bent, 3, -1.0f, 1.0f) == 0);
                    std::size_t skyNotOpen = 0;
                    for (int y = 0; y < H; ++y)
                        for (int x = 0; x < W; ++x)
                            if (at(background, x, y))
                                skyNotOpen += ao.at(x, y, 0) != 1.0f || bent.at(x, y, 0) != 0.0f || bent.at(x, y, 1) != 0.0f ||
                                              bent.at(x, y, 2) != 0.0f;
                    CHECK(skyNotOpen == 0);
                    aoTexture = out.ao;
                }
                for (const GiMethod method : {GiMethod::Screen, GiMethod::Hybrid}) {
                    CAPTURE(static_cast<int>(method));
                    const TextureView indirect = gi.run(adopted, poisonedGiSettings(method, resolution, blur, voxels)).radiance;
                    const Image light = readTexture(f.ctx, indirect);
                    CHECK(outsideCount(light, 3, 0.0f, 65504.0f) == 0);
                    std::size_t skyLit = 0, surfaceLit = 0;
                    for (int y = 0; y < H; ++y)
                        for (int x = 0; x < W; ++x) {
                            const bool lit = light.at(x, y, 0) + light.at(x, y, 1) + light.at(x, y, 2) > 0.0f;
                            (at(background, x, y) ? skyLit : surfaceLit) += lit;
                        }
                    CHECK(skyLit == 0);
                    CHECK(surfaceLit > surfaces / 2); // the box's walls light each other
                    ComposeSettings c;
                    c.ambient = glm::vec3(0.5f);
                    const Image display = readTexture(f.ctx, composer.compose({adopted, aoTexture, indirect}, c));
                    CHECK(outsideCount(display, 3, 0.0f, 1.0f) == 0);
                    const Image radiance = readTexture(f.ctx, composer.radiance());
                    const Image direct = readTexture(f.ctx, f.view.directRadiance);
                    std::size_t skyNotDirect = 0;
                    for (int y = 0; y < H; ++y)
                        for (int x = 0; x < W; ++x)
                            for (int ch = 0; ch < 3 && at(background, x, y); ++ch)
                                skyNotDirect += radiance.at(x, y, ch) != direct.at(x, y, ch);
                    CHECK(skyNotDirect == 0);
                }
            }
        }
        glDeleteTextures(1, &depth);
    }
    CHECK(test::drainGlErrors().empty());
}
