// Geometry tiles (AmbientOcclusionSettings::geometryTiles, shaders/filters/geometry_tiles.glsl):
// at half and quarter resolution the integrator, the blur and the upsampling run only over
// the tiles with geometry (the integrator only on their pixels with geometry), and the other
// tiles and pixels keep the background values they are cleared to. The
// documented promise is the same result as a dispatch over every tile, so the check is
// equality, bit for bit: each pixel's rays, sums and filter weights are the same
// computations either way; only the order of the refinement list differs, and each listed
// pixel is computed on its own (below the list's capacity, which these images stay far from).
#include "gl_fixture.hpp"
#include "integrator_settings.hpp"

#include "filters/guided_filters.hpp"
#include "obscura/assets.hpp"
#include "obscura/obscura.hpp"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>

using namespace obscura;

namespace {

// Odd and not square, so that the last tiles reach past the image; the Cornell box from far
// enough away that whole tiles are background around it. At half resolution 7 x 5 tiles,
// at quarter 4 x 3: one group of the marking pass (geometry_tiles.comp.glsl) each.
constexpr int kWidth = 97, kHeight = 75;
// Several marking groups, the last of them partly outside the tile grid: at half
// resolution 19 x 11 tiles (3 x 2 groups of 8 x 8), at quarter 10 x 6 (2 x 1).
constexpr glm::ivec2 kManyTiles{289, 161};

// From `distance` in front of the box, moved `shift` to the side (and `rise` up).
Camera cornellCamera(float distance, float shift = 0.0f, float rise = 0.0f, float aspect = float(kWidth) / float(kHeight)) {
    return Camera::perspective({{278 + shift, 273 + rise, -distance}, {278 + shift, 273 + rise, 0}, {0, 1, 0}},
                               glm::radians(45.0f), aspect, 10.0f, 8000.0f);
}

struct TileFixture {
    test::GlFixture gl;
    Context ctx{gl.desc()};
    GBuffer beforeBuffer{ctx}, frameBuffer{ctx}; // a G-buffer's views share its textures
    Voxelizer voxelizer{ctx};
    assets::LoadedScene cornell = assets::builtinScene("cornell");

    GBufferView render(GBuffer& gbuffer, const Camera& camera, glm::ivec2 size = {kWidth, kHeight}) {
        return gbuffer.render(cornell.scene, camera, {size.x, size.y, true, {}});
    }

    // The share of G-buffer pixels that show geometry.
    double coverage(GBuffer& gbuffer, const GBufferView& view) {
        const Image positions = readTexture(ctx, gbuffer.positions(view));
        int geometry = 0;
        for (int y = 0; y < view.height; ++y)
            for (int x = 0; x < view.width; ++x) geometry += positions.at(x, y, 3) > 0.0f;
        return double(geometry) / double(view.width * view.height);
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

    // Whether the profiler has timed a pass of this name since its last reset.
    bool ran(const std::string& pass) {
        const std::vector<PassStatistics> passes = ctx.profiler().statistics(true);
        return std::any_of(passes.begin(), passes.end(), [&](const PassStatistics& p) { return p.name == pass; });
    }
};

// Pixels whose bits differ between two images of the same size, or that hold a NaN.
int differingPixels(const Image& a, const Image& b) {
    REQUIRE(a.width == b.width);
    REQUIRE(a.height == b.height);
    REQUIRE(a.channels == b.channels);
    const std::size_t channels = std::size_t(a.channels);
    int differing = 0;
    for (std::size_t i = 0; i < a.pixels.size(); i += channels) {
        const auto first = a.pixels.begin() + std::ptrdiff_t(i), last = first + std::ptrdiff_t(channels);
        const bool nan = std::any_of(first, last, [](float v) { return std::isnan(v); });
        differing += nan || std::memcmp(&a.pixels[i], &b.pixels[i], sizeof(float) * channels) != 0;
    }
    return differing;
}

AmbientOcclusionSettings aoSettings(AoMethod method, AoResolution resolution, int blurTaps = 2) {
    auto s = test::integratorSettings<AmbientOcclusionSettings>(150.0f, 8, 6, resolution, blurTaps);
    s.method = method;
    s.bentNormals = true;
    return s;
}

IndirectLightSettings giSettings(GiMethod method, AoResolution resolution, int blurTaps = 2) {
    auto s = test::integratorSettings<IndirectLightSettings>(300.0f, 8, 6, resolution, blurTaps);
    s.method = method;
    return s;
}

// A module's run with geometry tiles against its run over every tile on `frame`, with fresh
// modules: pass `tilesPass` runs only in the first, and each texture `outputs` picks from
// the views is the same bit for bit.
template <class Module, class Settings, class Outputs>
void checkTiles(TileFixture& f, const GBufferView& frame, Settings s, const char* tilesPass, Outputs outputs) {
    Module tiled(f.ctx), everyTile(f.ctx);
    f.ctx.profiler().reset();
    s.geometryTiles = false;
    const auto b = everyTile.run(frame, s);
    CHECK_FALSE(f.ran(tilesPass));
    s.geometryTiles = true;
    const auto a = tiled.run(frame, s);
    CHECK(f.ran(tilesPass));
    const std::vector<TextureView> fromTiles = outputs(a), fromEvery = outputs(b);
    for (std::size_t i = 0; i < fromTiles.size(); ++i)
        CHECK(differingPixels(readTexture(f.ctx, fromTiles[i]), readTexture(f.ctx, fromEvery[i])) == 0);
}

void checkAo(TileFixture& f, const GBufferView& frame, const AmbientOcclusionSettings& s) {
    checkTiles<AmbientOcclusion>(f, frame, s, "ao.tiles", [&](const AmbientOcclusionView& v) {
        return s.bentNormals ? std::vector{v.ao, v.bentNormal} : std::vector{v.ao};
    });
}

void checkGi(TileFixture& f, const GBufferView& frame, const IndirectLightSettings& s) {
    checkTiles<IndirectLight>(f, frame, s, "gi.tiles", [](const IndirectLightView& v) { return std::vector{v.radiance}; });
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
    const VoxelGrid& grid = f.voxelizer.voxelize(f.cornell.scene, VoxelizerSettings{}); // the default resolution

    for (const AoResolution resolution : {AoResolution::Half, AoResolution::Quarter}) {
        CAPTURE(static_cast<int>(resolution));
        // AO
        for (const AoMethod method : {AoMethod::Points, AoMethod::Horizon, AoMethod::RayMarch})
            for (const int lanes : {1, 4}) {
                CAPTURE(static_cast<int>(method), lanes);
                AmbientOcclusionSettings s = aoSettings(method, resolution);
                s.rayLanes = lanes;
                checkAo(f, frame, s);
            }
        // Without refinement (the upsampling's plain variant), and voxel visibility.
        AmbientOcclusionSettings unrefined = aoSettings(AoMethod::Points, resolution);
        unrefined.refineThreshold = 0.0f;
        checkAo(f, frame, unrefined);
        AmbientOcclusionSettings voxel = aoSettings(AoMethod::Voxel, resolution);
        voxel.voxels = &grid;
        checkAo(f, frame, voxel);
        // 256 rays of 255 steps, 65536 loop iterations a pixel: more than a batch may take on
        // llvmpipe (src/core/ray_batches.hpp), so there the pass runs in two dispatches.
        AmbientOcclusionSettings batched = aoSettings(AoMethod::RayMarch, resolution);
        batched.rays = 256;
        batched.steps = 255;
        checkAo(f, frame, batched);
        // Indirect light, screen space with and without refinement (RGB MODULATE TILES), hybrid.
        checkGi(f, frame, giSettings(GiMethod::Screen, resolution));
        IndirectLightSettings giUnrefined = giSettings(GiMethod::Screen, resolution);
        giUnrefined.refineThreshold = 0.0f;
        checkGi(f, frame, giUnrefined);
        IndirectLightSettings hybrid = giSettings(GiMethod::Hybrid, resolution);
        hybrid.voxels = &grid;
        checkGi(f, frame, hybrid);
    }
}

TEST_CASE("Geometry tiles listed by several marking groups give the same images as every tile", "[filters][ao][gi]") {
    // The last marking group to finish lists the tiles of all of them (geometry_tiles.comp.glsl);
    // with one group, as above, the other groups' marks are never read.
    TileFixture f;
    const GBufferView frame =
        f.render(f.frameBuffer, cornellCamera(1300.0f, 0.0f, 0.0f, float(kManyTiles.x) / float(kManyTiles.y)), kManyTiles);
    const double coverage = f.coverage(f.frameBuffer, frame);
    CAPTURE(coverage);
    CHECK(coverage < 0.4); // most tiles hold no geometry
    CHECK(coverage > 0.1);
    for (const AoResolution resolution : {AoResolution::Half, AoResolution::Quarter}) {
        CAPTURE(static_cast<int>(resolution));
        checkAo(f, frame, aoSettings(AoMethod::Points, resolution));
        checkGi(f, frame, giSettings(GiMethod::Screen, resolution));
    }
}

TEST_CASE("Geometry tiles leave nothing of an earlier frame in the tiles they skip", "[filters][ao][gi]") {
    // The filters read low-resolution texels across tile edges. After a frame that showed the
    // box a little to the side, the tiles now background held its values, at the depths and
    // normals of the geometry beside them, so that any left there would weigh in. Some shift
    // puts the earlier edge across a tile border: the shifts cover two tiles of the quarter
    // resolution (64 G-buffer pixels, about 14 mm each at the box's front). A blur of 8 taps
    // reaches across a whole tile: with the low-resolution images left uncleared, 9128 and
    // 4567 AO pixels differ (with 2 to 4 taps none do here: the guide weights keep the earlier
    // values out). Indirect light's background value is 0, which drivers that zero new
    // textures (Mesa) give it anyway: only an earlier frame tells whether its clears run.
    TileFixture f;
    const GBufferView frame = f.render(f.frameBuffer, cornellCamera(1300.0f));
    for (const AoResolution resolution : {AoResolution::Half, AoResolution::Quarter}) {
        CAPTURE(static_cast<int>(resolution));
        AmbientOcclusionSettings s = aoSettings(AoMethod::Points, resolution, 8);
        IndirectLightSettings g = giSettings(GiMethod::Screen, resolution, 8);
        s.geometryTiles = g.geometryTiles = false;
        AmbientOcclusion aoEveryTile(f.ctx);
        IndirectLight giEveryTile(f.ctx);
        const AmbientOcclusionView expected = aoEveryTile.run(frame, s);
        const Image expectedAo = readTexture(f.ctx, expected.ao), expectedBent = readTexture(f.ctx, expected.bentNormal);
        const Image expectedRadiance = readTexture(f.ctx, giEveryTile.run(frame, g).radiance);
        s.geometryTiles = g.geometryTiles = true;
        AmbientOcclusion ao(f.ctx);
        IndirectLight gi(f.ctx);
        int aoDiffering = 0, giDiffering = 0;
        for (float shift = 15.0f; shift <= 900.0f; shift += 15.0f) {
            const GBufferView before = f.render(f.beforeBuffer, cornellCamera(1300.0f, shift));
            ao.run(before, s);
            gi.run(before, g);
            const AmbientOcclusionView a = ao.run(frame, s);
            aoDiffering += differingPixels(readTexture(f.ctx, a.ao), expectedAo) +
                           differingPixels(readTexture(f.ctx, a.bentNormal), expectedBent);
            giDiffering += differingPixels(readTexture(f.ctx, gi.run(frame, g).radiance), expectedRadiance);
        }
        CHECK(aoDiffering == 0);
        CHECK(giDiffering == 0);
    }
}

TEST_CASE("Images with more tiles than one indirect dispatch takes run every tile", "[filters]") {
    // GL 4.5 guarantees 65535 groups per dimension of a dispatch, and the tiles go in one
    // dimension: 65535 tiles of 8 x 8 reduced pixels fit, 65536 (2048 x 2048 reduced pixels,
    // a 4096 x 4096 G-buffer at half resolution) do not.
    using obscura::detail::GuidedFilters;
    CHECK(GuidedFilters::geometryTilesFit({8 * 65535, 8}));
    CHECK(GuidedFilters::geometryTilesFit({2048, 2040}));
    CHECK_FALSE(GuidedFilters::geometryTilesFit({2048, 2048}));
    CHECK_FALSE(GuidedFilters::geometryTilesFit({8 * 65536, 1}));
}

TEST_CASE("The refinement list never holds more pixels than one indirect dispatch's groups take", "[filters]") {
    // The refinement runs FILTER_REFINE_GROUP (64) listed pixels a group, dispatched indirectly
    // in one dimension, where GL 4.5 guarantees 65535 groups: the list holds a quarter of the
    // G-buffer's pixels up to 65535 x 64 = 4194240 (a 4096 x 4095 G-buffer's quarter fits,
    // 4096 x 4096's, 4194304, does not).
    using obscura::detail::GuidedFilters;
    constexpr std::size_t most = std::size_t{65535} * 64;
    CHECK(GuidedFilters::refineCapacity({16, 16}) == 64);
    CHECK(GuidedFilters::refineCapacity({97, 75}) == (97 * 75 + 3) / 4);
    CHECK(GuidedFilters::refineCapacity({4096, 4095}) == 4096 * 4095 / 4);
    CHECK(GuidedFilters::refineCapacity({4096, 4096}) == most);
    CHECK(GuidedFilters::refineCapacity({16384, 16384}) == most);
}
