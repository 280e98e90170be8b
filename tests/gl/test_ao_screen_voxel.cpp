// Screen space against voxel space: where nothing on the rays is hidden from the camera the two
// classify the same directions alike, up to each one's geometric error; where something is
// hidden, only the voxels see it.
#include "ao_fixture.hpp"

#include "obscura/obscura.hpp"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>

using namespace obscura;
using test::AoFixture;
using test::floorScene;
using test::lookAt;
using test::wallMean;

TEST_CASE("Screen and voxel AO of a floor in front of a visible wall differ only by the directions within their "
          "geometric error", "[ao]") {
    // The ray march and the voxel traversal take the same directions per pixel (aoDirection
    // with the pixel's rotation): a direction with component u toward the wall meets it at
    // t = D / u. The march calls it occluded iff t is at most its last sample, in
    // [r (1 - 1/steps), r]; the voxels iff the wall's voxels, up to a voxel side nearer
    // (conservative voxelization), are within r: t' = D' / u with D' in [D - side, D]. So
    // every direction the march finds occluded the voxels do too (screen AO >= voxel AO, per
    // pixel), and they can differ only for u in [(D - side) / r, D / (r (1 - 1/steps))], whose
    // cosine-weighted share is p = wallMean(D, r (1 - 1/steps)) - wallMean(D - side, r). The
    // camera looks down on the wall's face from above every ray's reach, so the depth buffer
    // holds every surface the rays meet.
    AoFixture f;
    const Scene scene = test::wallScene();
    constexpr int W = 96, H = 72;
    f.render(scene, test::wallCamera(W, H), W, H);
    constexpr double radius = 1.0;
    constexpr int rays = 1024, steps = 32;
    AmbientOcclusionSettings s;
    s.radius = static_cast<float>(radius);
    s.rays = rays;
    s.steps = steps;
    s.method = AoMethod::Voxel;
    const Image voxel = f.run(scene, s, test::wallVoxels());
    s.method = AoMethod::RayMarch;
    const auto never = [](double) { return 0.0; }; // AO: a hit occludes fully
    for (const ScreenMarch march : {ScreenMarch::View, ScreenMarch::Texture, ScreenMarch::HiZ}) {
        CAPTURE(static_cast<int>(march));
        s.march = march;
        const Image screen = f.run(scene, s);
        int checked = 0, differing = 0;
        double meanDifference = 0.0, meanShare = 0.0;
        for (int y = 0; y < H; ++y)
            for (int x = 0; x < W; ++x) {
                glm::dvec3 p;
                if (!test::wallFloorPixel(f, x, y, p)) continue;
                const double distance = p.z + 1.0;
                const double share = wallMean(distance, radius * (1.0 - 1.0 / steps), true, never) -
                                     wallMean(std::max(distance - test::kWallVoxelSide, 0.0), radius, true, never);
                // The number of a pixel's directions in that band, taken as binomial (the rotated
                // Hammersley set is stratified, so this is conservative): 5 sigma; and each
                // value's rounding to a half float (2^-12 below 1). The stratification also keeps
                // two rotations' estimates closer than this, so the bound checks where the two
                // geometries put the wall (a voxel ray 5 % short fails it), not that the
                // directions are shared.
                const double sigma = std::sqrt(std::max(share * (1.0 - share), 1.0 / rays) / rays);
                const double rounding = 2.0 * std::ldexp(1.0, -12);
                const double difference = double(screen.at(x, y, 0)) - voxel.at(x, y, 0);
                CAPTURE(x, y, distance, screen.at(x, y, 0), voxel.at(x, y, 0), share);
                CHECK(difference >= -rounding);
                CHECK(difference <= share + 5.0 * sigma + rounding);
                differing += difference != 0.0;
                meanDifference += difference;
                meanShare += share;
                ++checked;
            }
        INFO(checked << " floor pixels, " << differing << " differ; mean difference " << meanDifference / checked
                     << ", mean share of uncertain directions " << meanShare / checked);
        CHECK(checked > 200);
        // The mean difference is at most the mean share (every uncertain direction classified
        // apart), plus 5 sigma of the pixels' mean (independent rotations).
        CHECK(meanDifference / checked <= meanShare / checked + 5.0 * std::sqrt(meanShare / checked / (double(rays) * checked)) +
                                              2.0 * std::ldexp(1.0, -12));
    }
}

namespace {

// Floor points (y = 0) with |x| and z in a box.
struct FloorBox {
    double absXMin, absXMax, zMin, zMax;
    bool holds(glm::dvec3 p) const {
        return std::abs(p.y) <= 1e-3 && std::abs(p.x) > absXMin && std::abs(p.x) < absXMax && p.z > zMin && p.z < zMax;
    }
};

// Scenes with a ceiling slab at y = 1, x in [-slabX, slabX], z in [-6, -2], over the floor,
// where the camera does not see it: screen and voxel AO (r = 1.5) at floor pixels in `open`
// (more than the radius from the slab) are both exactly 1; in `covered` (at least 1.25 inside
// the slab's edges, so that it covers every direction that reaches the effective ceiling h,
// below, within the radius: horizontal reach r sqrt(1 - (h/r)^2) <= 1.23 for h >= 0.861) the
// voxels give AO_r = (h / r)^2 for the cosine-weighted hemisphere and the screen, which does
// not see the slab, 1.
void checkHiddenSlab(AoFixture& f, const Scene& scene, int W, int H, FloorBox open, FloorBox covered) {
    const VoxelizerSettings voxels = test::boxVoxels({-4.0f, -0.5f, -8.0f}, {4.0f, 3.5f, 0.0f});
    AmbientOcclusionSettings s;
    s.radius = 1.5f;
    s.rays = 256;
    s.steps = 32;
    const Image screen = f.run(scene, s);
    s.method = AoMethod::Voxel;
    const Image voxel = f.run(scene, s, voxels);
    // The voxel rays start lifted by a voxel diagonal (sqrt(3) x 8/128) and the slab's voxels
    // reach down by up to a voxel (4/128): the ceiling is effectively h in [0.861, 0.892].
    const double lift = std::sqrt(3.0) * 8.0 / 128.0, hMax = 1.0 - lift, hMin = hMax - 4.0 / 128.0;
    int openCount = 0, coveredCount = 0;
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) {
            if (!f.geometry(x, y)) continue;
            const glm::dvec3 p = f.world(x, y);
            CAPTURE(x, y, p.x, p.z, screen.at(x, y, 0), voxel.at(x, y, 0));
            if (open.holds(p)) {
                ++openCount;
                CHECK(screen.at(x, y, 0) == 1.0f);
                CHECK(voxel.at(x, y, 0) == 1.0f);
            } else if (covered.holds(p)) {
                ++coveredCount;
                const double lo = std::pow(hMin / 1.5, 2.0), hi = std::pow(hMax / 1.5, 2.0);
                // 5 sigma of 256 binomial directions, and the rounding to a half float.
                const double tolerance = 5.0 * std::sqrt(hi * (1.0 - lo) / 256.0) + std::ldexp(1.0, -12);
                CHECK(screen.at(x, y, 0) == 1.0f);
                CHECK(voxel.at(x, y, 0) >= lo - tolerance);
                CHECK(voxel.at(x, y, 0) <= hi + tolerance);
            }
        }
    CHECK(openCount > 10);
    CHECK(coveredCount > 10);
}

Scene floorWithSlab(double slabX) {
    Scene scene = floorScene(10.0);
    const Scene slab = test::quadScene({{{glm::dvec3(-slabX, 1, -6), {slabX, 1, -6}, {slabX, 1, -2}, {-slabX, 1, -2}}},
                                        {{glm::dvec3(-slabX, 1, -2), {slabX, 1, -2}, {slabX, 1, -6}, {-slabX, 1, -6}}}});
    for (const Mesh& m : slab.meshes) scene.meshes.push_back(m);
    return scene;
}

} // namespace

TEST_CASE("Screen space and voxel space agree where nothing is hidden and differ where something is", "[ao]") {
    AoFixture f;
    // The slab seen exactly edge-on: the depth buffer never holds it, the voxel grid does.
    const Scene scene = floorWithSlab(3.0);
    constexpr int W = 96, H = 64;
    f.render(scene, lookAt({0, 1, 4}, {0, 1, -4}, W, H), W, H);
    checkHiddenSlab(f, scene, W, H, {0.0, 2.0, -0.4, 0.0}, {0.0, 1.75, -4.75, -3.25});
}

TEST_CASE("Screen space misses an occluder hidden behind another object, voxel space finds it", "[ao]") {
    AoFixture f;
    // A curtain in the plane z = 0 from y = 0.63 up, facing the camera at (0, 0.6, 1): the
    // camera sees the floor behind it through the gap below (its rays there stay below 0.6),
    // but the slab's underside only through the curtain (its rays cross z = 0 at heights
    // 0.6 + 0.4 / (1 - z) in [0.657, 0.733] for z in [-6, -2]).
    Scene scene = floorWithSlab(1.5);
    const Scene curtain = test::quadScene({{{glm::dvec3(-6, 0.63, 0), {6, 0.63, 0}, {6, 3, 0}, {-6, 3, 0}}}});
    for (const Mesh& m : curtain.meshes) scene.meshes.push_back(m);
    constexpr int W = 144, H = 96;
    f.render(scene, lookAt({0, 0.6f, 1}, {0, 0.3f, -4}, W, H), W, H);
    int onCurtain = 0, onSlab = 0;
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) {
            if (!f.geometry(x, y)) continue;
            const glm::dvec3 p = f.world(x, y);
            onCurtain += std::abs(p.z) < 1e-3 && p.y > 0.6;
            onSlab += std::abs(p.y - 1.0) < 1e-3 && p.z < -1.0;
        }
    CHECK(onCurtain > W * H / 4);
    CHECK(onSlab == 0);
    // Open: beside the slab, more than the radius from it (3.1 - 1.5 > 1.5) and from the
    // curtain; covered: under its middle (|x| < 1.5 - 1.25).
    checkHiddenSlab(f, scene, W, H, {3.1, 3.9, -4.75, -3.25}, {0.0, 0.25, -4.75, -3.25});
}

TEST_CASE("Voxel AO with a radius far past the grid sees what a radius just past it sees", "[ao][stability]") {
    // The wall scene's grid is 4 m a side in 128 voxels: a radius of 1e3 m ends rays 3.2e4
    // voxels out, within the traversals' coordinate limit (2^24), one of 1e9 m 3.2e10 out,
    // past it. Past the grid nothing is hit, so AO (a hit occludes fully, however far) and the
    // bent normal (of the open directions) must be the same with either radius, for the
    // traversals that visit every voxel on the segment (the march samples `steps` points along
    // it, spread with the length, so it is not expected to agree). Not quite bit for bit
    // everywhere: the two segments' ends, snapped to the traversal's 1/4096-voxel grid, may
    // round apart, turning a ray that grazes a voxel's corner; on llvmpipe no value differs,
    // and a handful (1 % of the values) is allowed. Before the long rays were shortened to the
    // limit, every one of them counted as open: AO 1 (6900 values differed).
    AoFixture f;
    const Scene scene = test::wallScene();
    constexpr int W = 48, H = 36;
    f.render(scene, test::wallCamera(W, H), W, H);
    AmbientOcclusionSettings s;
    s.method = AoMethod::Voxel;
    s.rays = 64;
    s.bentNormals = true;
    s.voxels = &f.voxelizer.voxelize(scene, test::wallVoxels());
    for (const VoxelTraversal traversal : {VoxelTraversal::Exact, VoxelTraversal::Hierarchical}) {
        CAPTURE(static_cast<int>(traversal));
        s.voxelTraversal = traversal;
        s.radius = 1e3f;
        const AmbientOcclusionView nearRun = f.ao.run(f.view, s);
        const Image ao = readTexture(f.ctx, nearRun.ao), bent = readTexture(f.ctx, nearRun.bentNormal);
        s.radius = 1e9f;
        const AmbientOcclusionView farRun = f.ao.run(f.view, s);
        const Image farAo = readTexture(f.ctx, farRun.ao), farBent = readTexture(f.ctx, farRun.bentNormal);
        int occluded = 0, differing = 0, values = 0;
        for (int y = 0; y < H; ++y)
            for (int x = 0; x < W; ++x) {
                if (!f.geometry(x, y)) continue;
                occluded += ao.at(x, y, 0) < 1.0f;
                values += 4;
                differing += ao.at(x, y, 0) != farAo.at(x, y, 0);
                for (int c = 0; c < 3; ++c) differing += bent.at(x, y, c) != farBent.at(x, y, c);
            }
        CHECK(occluded > W * H / 4); // the wall and the floor occlude each other's pixels
        CHECK(differing <= values / 100);
    }
}
