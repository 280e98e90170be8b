// Geometry tiles (AmbientOcclusionSettings::geometryTiles, shaders/filters/geometry_tiles.glsl):
// at half and quarter resolution the integrator, the blur and the upsampling run only over
// the tiles with geometry, and the other tiles are cleared to the background values. The
// documented promise is the same result as a dispatch over every tile, so the check is
// equality, bit for bit: each pixel's rays, sums and filter weights are the same
// computations either way; only the order of the refinement list differs, and each listed
// pixel is computed on its own.
#include "gl_fixture.hpp"

#include "obscura/assets.hpp"
#include "obscura/obscura.hpp"

#include <catch2/catch.hpp>

#include <cmath>
#include <cstring>

using namespace obscura;

namespace {

// Odd and not square, so that the last tiles reach past the image; the Cornell box from far
// enough away that whole tiles are background around it.
constexpr int kWidth = 97, kHeight = 75;

// From `distance` in front of the box, moved `shift` to the side (and `rise` up).
Camera cornellCamera(float distance, float shift = 0.0f, float rise = 0.0f) {
    return Camera::perspective({{278 + shift, 273 + rise, -distance}, {278 + shift, 273 + rise, 0}, {0, 1, 0}},
                               glm::radians(45.0f), float(kWidth) / float(kHeight), 10.0f, 8000.0f);
}

struct TileFixture {
    test::GlFixture gl;
    Context ctx{gl.desc()};
    GBuffer beforeBuffer{ctx}, frameBuffer{ctx}; // a G-buffer's views share its textures
    assets::LoadedScene cornell = assets::builtinScene("cornell");

    GBufferView render(GBuffer& gbuffer, const Camera& camera) {
        return gbuffer.render(cornell.scene, camera, {kWidth, kHeight, true, {}});
    }

    // The share of G-buffer pixels that show geometry.
    double coverage(GBuffer& gbuffer, const GBufferView& view) {
        const Image positions = readTexture(ctx, gbuffer.positions(view));
        int geometry = 0;
        for (int y = 0; y < kHeight; ++y)
            for (int x = 0; x < kWidth; ++x) geometry += positions.at(x, y, 3) > 0.0f;
        return double(geometry) / double(kWidth * kHeight);
    }

    // Whether geometry reaches the image's last column and its top row (GL's last row): the
    // tiles that reach past the image.
    bool reachesFarEdges(GBuffer& gbuffer, const GBufferView& view) {
        const Image positions = readTexture(ctx, gbuffer.positions(view)); // row 0: the top
        bool lastColumn = false, topRow = false;
        for (int y = 0; y < kHeight; ++y) lastColumn = lastColumn || positions.at(kWidth - 1, y, 3) > 0.0f;
        for (int x = 0; x < kWidth; ++x) topRow = topRow || positions.at(x, 0, 3) > 0.0f;
        return lastColumn && topRow;
    }
};

// Pixels whose bits differ between two images of the same size (NaN included: none is equal).
int differingPixels(const Image& a, const Image& b) {
    REQUIRE(a.width == b.width);
    REQUIRE(a.height == b.height);
    REQUIRE(a.channels == b.channels);
    int differing = 0;
    for (std::size_t i = 0; i < a.pixels.size(); i += std::size_t(a.channels))
        differing += std::memcmp(&a.pixels[i], &b.pixels[i], sizeof(float) * std::size_t(a.channels)) != 0 ||
                     std::isnan(a.pixels[i]);
    return differing;
}

AmbientOcclusionSettings aoSettings(AoMethod method, AoResolution resolution, int blurTaps = 2) {
    AmbientOcclusionSettings s;
    s.method = method;
    s.radius = 150.0f;
    s.rays = 8;
    s.steps = 6;
    s.resolution = resolution;
    s.blurRadius = blurTaps;
    s.bentNormals = method != AoMethod::Horizon;
    return s;
}

} // namespace

TEST_CASE("Geometry tiles give AO, bent normals and indirect light bit for bit as a dispatch over every tile",
          "[filters][ao][gi]") {
    TileFixture f;
    const bool corner = GENERATE(false, true);
    // Centred, the box leaves most tiles background; in the top right corner it reaches into
    // the tiles that reach past the image (odd sizes).
    const GBufferView frame =
        f.render(f.frameBuffer, corner ? cornellCamera(1300.0f, 500.0f, -350.0f) : cornellCamera(1300.0f));
    const double coverage = f.coverage(f.frameBuffer, frame);
    CAPTURE(corner, coverage);
    CHECK(coverage < 0.4); // most tiles hold no geometry
    CHECK(coverage > 0.1);
    CHECK(f.reachesFarEdges(f.frameBuffer, frame) == corner);

    for (const AoResolution resolution : {AoResolution::Half, AoResolution::Quarter}) {
        CAPTURE(static_cast<int>(resolution));
        SECTION("AO") {
            for (const AoMethod method : {AoMethod::Points, AoMethod::Horizon, AoMethod::RayMarch})
                for (const int lanes : {1, 4}) {
                    CAPTURE(static_cast<int>(method), lanes);
                    AmbientOcclusionSettings s = aoSettings(method, resolution);
                    s.rayLanes = lanes;
                    AmbientOcclusion tiled(f.ctx), everyTile(f.ctx);
                    const AmbientOcclusionView a = tiled.run(frame, s);
                    s.geometryTiles = false;
                    const AmbientOcclusionView b = everyTile.run(frame, s);
                    CHECK(differingPixels(readTexture(f.ctx, a.ao), readTexture(f.ctx, b.ao)) == 0);
                    if (s.bentNormals)
                        CHECK(differingPixels(readTexture(f.ctx, a.bentNormal), readTexture(f.ctx, b.bentNormal)) == 0);
                }
        }
        SECTION("indirect light") {
            IndirectLightSettings s;
            s.radius = 300.0f;
            s.rays = 8;
            s.steps = 6;
            s.resolution = resolution;
            s.blurRadius = 2;
            IndirectLight tiled(f.ctx), everyTile(f.ctx);
            const IndirectLightView a = tiled.run(frame, s);
            s.geometryTiles = false;
            const IndirectLightView b = everyTile.run(frame, s);
            CHECK(differingPixels(readTexture(f.ctx, a.radiance), readTexture(f.ctx, b.radiance)) == 0);
        }
    }
}

TEST_CASE("Geometry tiles leave nothing of an earlier frame in the tiles they skip", "[filters][ao]") {
    // The filters read low-resolution texels across tile edges. After a frame that showed the
    // box a little to the side, the tiles now background held its values, at the depths and
    // normals of the geometry beside them, so that any left there would weigh in. Some shift
    // puts the earlier edge across a tile border: the shifts cover two tiles of the quarter
    // resolution (64 G-buffer pixels, about 14 mm each at the box's front). A blur of 8 taps
    // reaches across a whole tile: with the low-resolution images left uncleared, 9128 and
    // 4567 pixels differ (with 2 to 4 taps none do here: the guide weights keep the earlier
    // values out).
    TileFixture f;
    const GBufferView frame = f.render(f.frameBuffer, cornellCamera(1300.0f));
    for (const AoResolution resolution : {AoResolution::Half, AoResolution::Quarter}) {
        CAPTURE(static_cast<int>(resolution));
        AmbientOcclusionSettings s = aoSettings(AoMethod::Points, resolution, 8);
        s.geometryTiles = false;
        AmbientOcclusion everyTile(f.ctx);
        const AmbientOcclusionView expected = everyTile.run(frame, s);
        const Image expectedAo = readTexture(f.ctx, expected.ao), expectedBent = readTexture(f.ctx, expected.bentNormal);
        s.geometryTiles = true;
        AmbientOcclusion tiled(f.ctx);
        int differing = 0;
        for (float shift = 15.0f; shift <= 900.0f; shift += 15.0f) {
            tiled.run(f.render(f.beforeBuffer, cornellCamera(1300.0f, shift)), s);
            const AmbientOcclusionView a = tiled.run(frame, s);
            differing += differingPixels(readTexture(f.ctx, a.ao), expectedAo) +
                         differingPixels(readTexture(f.ctx, a.bentNormal), expectedBent);
        }
        CHECK(differing == 0);
    }
}
