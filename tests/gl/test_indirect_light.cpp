// One-bounce indirect light: a closed form (a floor lit by an emissive wall), screen space
// against the hybrid around a hidden occluder, zero where nothing is lit, stability, post-process
// mode, a projection mirrored in y, and the inputs it refuses (what rays gather from faces and albedo:
// test_indirect_light_gather.cpp).
#include "ao_fixture.hpp"
#include "gl_fixture.hpp"
#include "integrator_settings.hpp"
#include "mirrored_view.hpp"
#include "scene_builders.hpp"

#include "obscura/assets.hpp"
#include "obscura/obscura.hpp"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

using namespace obscura;
using test::wallCamera;

namespace {

constexpr double kPi = 3.14159265358979323846;

// As in test_ambient_occlusion.cpp: the share of cosine-weighted directions from a floor
// point at distance D from an infinite wall that reach the wall within r.
double wallShare(double distance, double radius) {
    const double c = distance / radius;
    if (c >= 1.0) return 0.0;
    return (std::acos(c) - c * std::sqrt(1.0 - c * c)) / kPi;
}

// The share of cosine-weighted directions from a floor point at distance d from an infinite
// wall that meet it below height h: they project onto the unit disc's points (u toward the
// wall, v along it) outside the ellipse u^2 (1 + h^2 / d^2) + v^2 = 1 with u > 0, of area
// pi/2 (1 - d / sqrt(d^2 + h^2)), over pi.
double footShare(double d, double h) { return 0.5 * (1.0 - d / std::sqrt(d * d + h * h)); }

// Whether the part of the wall z = -1 within `radius` of the floor point p is on screen: the
// half disc's arc and base, a convex set, inside the view volume (its vertices, 65 on the
// arc, with a margin of a hundredth of the screen for the arc between them).
bool wallInView(const Camera& camera, glm::dvec3 p, double radius) {
    const double d = p.z + 1.0, rho = std::sqrt(std::max(radius * radius - d * d, 0.0));
    const glm::dmat4 toClip = glm::dmat4(camera.projection) * glm::dmat4(camera.view);
    for (int i = 0; i <= 64; ++i) {
        const double phi = kPi * i / 64;
        const glm::dvec4 c = toClip * glm::dvec4(p.x + rho * std::cos(phi), rho * std::sin(phi), -1.0, 1.0);
        if (c.w <= 0.0 || std::abs(c.x / c.w) > 0.98 || std::abs(c.y / c.w) > 0.98) return false;
    }
    return true;
}

// How high up the wall z = -1 a point at most `side` in front of it can fall in a pixel
// whose centre shows the floor: the highest vertex, over those pixels, of the part of that
// slab inside the pixel's frustum, where the frustum's corner rays cross its two planes (y
// is linear and the part convex; corner rays that never reach the wall only go down, as the
// first CHECK makes sure, so they lower it).
double floorPixelsReach(const Camera& camera, const Image& positions, const glm::dmat4& toWorld, int width, int height,
                        double side) {
    const glm::dmat4 toClip = glm::dmat4(camera.projection) * glm::dmat4(camera.view), fromClip = glm::inverse(toClip);
    const auto unproject = [&](glm::dvec2 ndc, double z) {
        const glm::dvec4 w = fromClip * glm::dvec4(ndc, z, 1.0);
        return glm::dvec3(w) / w.w;
    };
    double reach = 0.0;
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            if (positions.at(x, y, 3) == 0.0f) continue;
            const glm::dvec3 p = test::worldPoint(positions, toWorld, x, y);
            if (std::abs(p.y) > 1e-3) continue;
            const glm::dvec4 c = toClip * glm::dvec4(p, 1.0);
            const glm::dvec2 centre = glm::dvec2(c) / c.w, half(1.0 / width, 1.0 / height);
            for (int k = 0; k < 4; ++k) {
                const glm::dvec2 corner = centre + half * glm::dvec2(k & 1 ? 1.0 : -1.0, k & 2 ? 1.0 : -1.0);
                const glm::dvec3 from = unproject(corner, -1.0), d = unproject(corner, 0.0) - from;
                CHECK(d.y < 0.0);
                if (d.z >= 0.0) continue;
                for (const double plane : {-1.0, -1.0 + side}) reach = std::max(reach, from.y + d.y * (plane - from.z) / d.z);
            }
        }
    return reach;
}

constexpr glm::vec3 kWallEmission(2.0f, 1.0f, 0.5f);

// test::wallScene: a grey floor, and the wall z = -1 emitting kWallEmission toward the floor
// (its own albedo plays no part: one bounce).
Scene emissiveWallScene() {
    Scene scene = test::wallScene();
    Material wall;
    wall.albedo = glm::vec3(0.0f);
    wall.emission = kWallEmission;
    scene.materials.push_back(wall);
    scene.meshes[1].material = 1;
    return scene;
}

// The emissive wall scene and the modules that render, voxelize and light it.
struct WallLight {
    test::GlFixture gl;
    Context ctx{gl.desc()};
    GBuffer gbuffer{ctx};
    Voxelizer voxelizer{ctx};
    IndirectLight gi{ctx};
    const Scene scene = emissiveWallScene();
};

// The share of a floor pixel's cosine-weighted directions that gather the wall's light, as a
// window [lo, hi] per method (L1 = rho Le share): as for AO, marching misses hits beyond its
// last sample, voxels bring the wall up to a side closer, and a voxel hit at the wall's foot
// may fall in a pixel that shows the floor (below footReach, floorPixelsReach), and be lost.
std::pair<double, double> wallLightWindow(GiMethod method, double distance, double radius, int steps,
                                          double voxelSide, double footReach) {
    if (method == GiMethod::Screen) return {wallShare(distance, radius * (1.0 - 1.0 / steps)), wallShare(distance, radius)};
    return {wallShare(distance, radius) - footShare(distance, footReach),
            wallShare(std::max(distance - voxelSide, 0.0), radius)};
}

// Checks pixel (x, y)'s light against rho Le times the share window [lo, hi] of `rays`
// directions: 5 sigma of the share (binomial), and the 16-bit float output (2^-11 relative).
void checkWallLight(const Image& radiance, const Image& albedo, int x, int y, double lo, double hi, int rays) {
    const double sigma = std::sqrt(std::max({lo * (1.0 - lo), hi * (1.0 - hi), 1.0 / rays}) / rays);
    for (int c = 0; c < 3; ++c) {
        const double scale = albedo.at(x, y, c) * kWallEmission[c];
        const double tolerance = scale * 5.0 * sigma + std::ldexp(scale, -11);
        const double value = radiance.at(x, y, c);
        CAPTURE(x, y, c, value, scale * lo, scale * hi);
        CHECK(value >= scale * lo - tolerance);
        CHECK(value <= scale * hi + tolerance);
    }
    CHECK(radiance.at(x, y, 3) == 1.0f);
}

} // namespace

TEST_CASE("A floor lit by an emissive wall matches the closed form within the sampling error in perspective, "
          "reversed-Z and orthographic views", "[gi]") {
    WallLight f;
    auto& [gl, ctx, gbuffer, voxelizer, gi, scene] = f;
    constexpr int W = 96, H = 72;
    constexpr double radius = 1.0;
    constexpr int rays = 1024, steps = 32;
    // Hybrid: cubic voxels of side 4/128 and 4/512, the wall seen from in front and nearly
    // edge-on (from 0.5 in front of its plane, 2.7 away: a pixel of it spans about 0.2 in
    // depth). The finer grid's default tolerance, two voxel diagonals (0.027), is far less
    // than that: a hit must be compared with the plane of the surface the pixel shows, not
    // with the depth at the pixel's centre.
    const Camera grazing = Camera::perspective({{2.6f, 1.2f, -0.5f}, {-0.3f, 0.2f, 0.2f}, {0, 1, 0}}, glm::radians(50.0f),
                                               float(W) / float(H), 0.05f, 200.0f);
    // The closed form holds for any projection whose depth buffer holds the floor and the
    // wall: wallCamera's view with reversed depth and an infinite far plane, and orthographic
    // (half height: the perspective view's at the target, 4.7 x tan 25 degrees) with reversed
    // and with [0, 1] depth. (floorPixelsReach unprojects depth -1 and 0 as near and far: not
    // for reversed depth, hence the hybrid method's orthographic view in [0, 1] depth.)
    const LookAt look{{0, 2.5f, 3.5f}, {0, 0.3f, -0.6f}, {0, 1, 0}};
    const float aspect = float(W) / float(H), halfHeight = 4.7f * std::tan(glm::radians(25.0f));
    struct Run {
        const char* name;
        GiMethod method;
        int resolution;
        Camera camera;
    };
    const std::vector<Run> runs = {
        {"screen", GiMethod::Screen, 0, wallCamera(W, H)},
        {"hybrid 128", GiMethod::Hybrid, 128, wallCamera(W, H)},
        {"hybrid 512", GiMethod::Hybrid, 512, wallCamera(W, H)},
        {"hybrid 512, grazing", GiMethod::Hybrid, 512, grazing},
        {"screen, reversed-Z, infinite far", GiMethod::Screen, 0,
         Camera::perspective(look, glm::radians(50.0f), aspect, 0.05f, INFINITY, DepthMode::Reversed)},
        {"screen, orthographic, reversed", GiMethod::Screen, 0,
         Camera::orthographic(look, halfHeight, aspect, 0.05f, 200.0f, DepthMode::Reversed)},
        {"hybrid 128, orthographic, zero to one", GiMethod::Hybrid, 128,
         Camera::orthographic(look, halfHeight, aspect, 0.05f, 200.0f, DepthMode::StandardZeroToOne)}};
    for (const Run& run : runs) {
        const GiMethod method = run.method;
        CAPTURE(run.name);
        const GBufferView view = gbuffer.render(scene, run.camera, {W, H, false, {}});
        const Image positions = readTexture(ctx, gbuffer.positions(view));
        const Image albedo = readTexture(ctx, view.albedo);
        const glm::dmat4 toWorld = glm::inverse(glm::dmat4(view.camera.view));
        const double voxelSide = 4.0 / std::max(run.resolution, 1);
        IndirectLightSettings s;
        s.method = method;
        s.radius = static_cast<float>(radius);
        s.rays = rays;
        s.steps = steps;
        if (method == GiMethod::Hybrid) s.voxels = &voxelizer.voxelize(scene, test::wallVoxels(run.resolution));
        const Image radiance = readTexture(ctx, gi.run(view, s).radiance);
        const double footReach = method == GiMethod::Hybrid ? floorPixelsReach(view.camera, positions, toWorld, W, H, voxelSide) : 0.0;
        INFO("hits below " << footReach << " on the wall may fall in the floor's pixels");
        int checked = 0;
        for (int y = 10; y < H; ++y)
            for (int x = 12; x < W - 12; ++x) {
                if (positions.at(x, y, 3) == 0.0f) continue;
                const glm::dvec3 p = test::worldPoint(positions, toWorld, x, y);
                if (std::abs(p.y) > 1e-3 || std::abs(p.x) > 0.8 || p.z > 1.2) continue;
                const double distance = p.z + 1.0;
                if (!wallInView(view.camera, p, radius)) continue; // hits off screen read nothing
                const auto [lo, hi] = wallLightWindow(method, distance, radius, steps, voxelSide, footReach);
                CAPTURE(distance);
                checkWallLight(radiance, albedo, x, y, lo, hi, rays);
                ++checked;
            }
        CHECK(checked > 200);
    }
}

TEST_CASE("Screen-space and hybrid indirect light agree where nothing is hidden and differ where an occluder "
          "the camera does not see stands between the floor and the light", "[gi]") {
    // emissiveWallScene with a fin, the plane x = -0.5 from the floor up to 3 and from the wall
    // out to z = 1, seen exactly edge-on (the camera is in its plane), so that no pixel holds
    // it. Screen-space rays pass it; hybrid rays meet its voxels.
    test::GlFixture gl;
    Context ctx(gl.desc());
    GBuffer gbuffer(ctx);
    Voxelizer voxelizer(ctx);
    IndirectLight gi(ctx);
    constexpr double finX = -0.5, radius = 1.0;
    Scene scene = emissiveWallScene();
    const Scene fin = test::quadScene({{{glm::dvec3(finX, 0, -1), {finX, 3, -1}, {finX, 3, 1}, {finX, 0, 1}}}});
    scene.meshes.push_back(fin.meshes[0]);
    constexpr int W = 128, H = 96, rays = 1024, steps = 32, resolution = 512;
    const Camera camera = Camera::perspective({{float(finX), 2.5f, 3.5f}, {float(finX), 0.3f, -0.6f}, {0, 1, 0}},
                                              glm::radians(50.0f), float(W) / float(H), 0.05f, 200.0f);
    const GBufferView view = gbuffer.render(scene, camera, {W, H, false, {}});
    const Image positions = readTexture(ctx, gbuffer.positions(view));
    const Image albedo = readTexture(ctx, view.albedo);
    const glm::dmat4 toWorld = glm::inverse(glm::dmat4(view.camera.view));
    IndirectLightSettings s;
    s.radius = static_cast<float>(radius);
    s.rays = rays;
    s.steps = steps;
    const Image screen = readTexture(ctx, gi.run(view, s).radiance);
    s.method = GiMethod::Hybrid;
    s.voxels = &voxelizer.voxelize(scene, test::wallVoxels(resolution));
    const Image hybrid = readTexture(ctx, gi.run(view, s).radiance);
    const double side = 4.0 / resolution;
    // The hybrid method's default thickness, two voxel diagonals: a voxel hit reads the wall's
    // light only within it of the wall's plane.
    const double reach = 2.0 * std::sqrt(3.0) * side;
    const double footReach = floorPixelsReach(view.camera, positions, toWorld, W, H, side);
    int finPixels = 0, open = 0, behindFin = 0;
    double meanGap = 0.0, meanGapBound = 0.0;
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) {
            if (positions.at(x, y, 3) == 0.0f) continue;
            const glm::dvec3 p = test::worldPoint(positions, toWorld, x, y);
            finPixels += std::abs(p.x - finX) < 1e-3 && p.y > 1e-3 && p.z > -1.0 + 1e-3;
            const double distance = p.z + 1.0, beside = p.x - finX;
            if (std::abs(p.y) > 1e-3 || distance < 0.1 || distance > 0.7 || !wallInView(view.camera, p, radius)) continue;
            CAPTURE(x, y, p.x, distance);
            if (beside > radius + side && p.x + radius < 2.0) {
                // Out of the fin's reach, and with the wall within the radius inside the voxel
                // grid (x < 2): both methods gather the whole wall, as in the test above.
                ++open;
                for (const GiMethod method : {GiMethod::Screen, GiMethod::Hybrid}) {
                    const auto [lo, hi] = wallLightWindow(method, distance, radius, steps, side, footReach);
                    checkWallLight(method == GiMethod::Screen ? screen : hybrid, albedo, x, y, lo, hi, rays);
                }
            } else if (beside > 0.0 && beside < 0.1) {
                // Beside the fin. The screen still sees the whole wall. A hybrid ray gathers light
                // only if it reaches the plane z = -1 + reach (distance - reach away) at x >= finX
                // (else the fin's voxels stop it farther than `reach` from the wall): within the
                // radius, half the directions that reach that plane, plus those whose hit lies
                // between finX and the pixel's own x: toward the wall, on the fin's side, within
                // an azimuth of atan(beside / d), and cosine-weighted directions spread their
                // azimuth evenly, so a share of atan(beside / d) / (2 pi). Rays above the fin's
                // top (3) are beyond the radius.
                ++behindFin;
                const double d = distance - reach;
                const auto [screenLo, screenHi] = wallLightWindow(GiMethod::Screen, distance, radius, steps, side, 0.0);
                const double hybridHi = 0.5 * wallShare(d, radius) + std::atan(beside / d) / (2.0 * kPi);
                checkWallLight(screen, albedo, x, y, screenLo, screenHi, rays);
                checkWallLight(hybrid, albedo, x, y, 0.0, hybridHi, rays);
                meanGap += (screen.at(x, y, 0) - hybrid.at(x, y, 0)) / (albedo.at(x, y, 0) * kWallEmission[0]);
                meanGapBound += screenLo - hybridHi;
            }
        }
    INFO(open << " open floor pixels, " << behindFin << " beside the fin");
    CHECK(finPixels == 0);
    CHECK(open > 50);
    REQUIRE(behindFin > 10);
    // The screen finds more light beside the fin: on average at least the windows' gap, less
    // 5 sigma of the mean. A pixel's two estimates share its directions, so their difference's
    // deviation is at most the sum of theirs (each at most 0.5 / sqrt(rays)); the pixels'
    // rotations are independent.
    meanGap /= behindFin;
    meanGapBound /= behindFin;
    INFO("mean gap " << meanGap << ", bound " << meanGapBound);
    CHECK(meanGapBound > 0.05);
    CHECK(meanGap >= meanGapBound - 5.0 / std::sqrt(double(rays) * behindFin));
}


TEST_CASE("A lit open plane gives exactly no indirect light for every method march resolution and projection", "[gi]") {
    // Every ray leaves the plane upward into the empty sky, so E_ind = 0 exactly: the plane's
    // own radiance must not come back through its tangent-plane tests, at any projection.
    test::GlFixture gl;
    Context ctx(gl.desc());
    GBuffer gbuffer(ctx);
    IndirectLight gi(ctx);
    Voxelizer voxelizer(ctx);
    const Scene scene = test::withSun(test::floorScene(50.0));
    constexpr int W = 64, H = 48;
    const LookAt look{{0, 3, 6}, {0, 0, 0}, {0, 1, 0}};
    const std::pair<const char*, Camera> projections[] = {
        {"perspective", Camera::perspective(look, glm::radians(50.0f), float(W) / H, 0.05f, 200.0f)},
        {"reversed-Z, infinite far",
         Camera::perspective(look, glm::radians(50.0f), float(W) / H, 0.05f, INFINITY, DepthMode::Reversed)},
        {"orthographic, zero to one", Camera::orthographic(look, 3.0f, float(W) / H, 0.05f, 200.0f, DepthMode::StandardZeroToOne)},
        // Far / near = 1e10, standard depth: a float step of depth spans 0.4 % of the view
        // distance here (as in the AO open-plane test).
        {"perspective, near 1e-4 far 1e6", Camera::perspective(look, glm::radians(50.0f), float(W) / H, 1e-4f, 1e6f)},
    };
    struct Variant {
        GiMethod method;
        ScreenMarch march;
        ScreenThickness thickness = ScreenThickness::Constant;
    };
    for (const auto& [name, camera] : projections) {
        GBufferSettings layers{W, H, true, {}};
        layers.depthLayers = 2; // for the peeling modes (the plane has no second layer)
        const GBufferView view = gbuffer.render(scene, camera, layers);
        const Image direct = readTexture(ctx, view.directRadiance);
        for (const Variant variant : {Variant{GiMethod::Screen, ScreenMarch::View}, Variant{GiMethod::Screen, ScreenMarch::Texture},
                                      Variant{GiMethod::Screen, ScreenMarch::HiZ}, Variant{GiMethod::Hybrid, ScreenMarch::View},
                                      Variant{GiMethod::Screen, ScreenMarch::HiZ, ScreenThickness::DepthPeeling},
                                      Variant{GiMethod::Screen, ScreenMarch::View, ScreenThickness::PeelingOrConstant}})
            for (AoResolution resolution : {AoResolution::Full, AoResolution::Half, AoResolution::Quarter}) {
                CAPTURE(name, static_cast<int>(variant.method), static_cast<int>(variant.march),
                        static_cast<int>(variant.thickness), static_cast<int>(resolution));
                IndirectLightSettings s;
                s.method = variant.method;
                s.march = variant.march;
                s.thicknessMode = variant.thickness;
                s.radius = 2.0f;
                s.rays = 24;
                s.resolution = resolution;
                s.blurRadius = resolution == AoResolution::Full ? 0 : 2;
                VoxelizerSettings grid;
                grid.resolution = 64;
                if (variant.method == GiMethod::Hybrid) s.voxels = &voxelizer.voxelize(scene, grid);
                const Image radiance = readTexture(ctx, gi.run(view, s).radiance);
                std::size_t lit = 0, notZero = 0;
                for (int y = 0; y < H; ++y)
                    for (int x = 0; x < W; ++x) {
                        lit += direct.at(x, y, 0) > 0.0f;
                        for (int c = 0; c < 3; ++c) notZero += radiance.at(x, y, c) != 0.0f;
                    }
                CHECK(lit > std::size_t(W * H / 2)); // the plane is lit: there is light to leak
                CHECK(notZero == 0);
            }
    }
}

TEST_CASE("Nothing lit gives no indirect light and the sky stays empty", "[gi]") {
    test::GlFixture gl;
    Context ctx(gl.desc());
    GBuffer gbuffer(ctx);
    IndirectLight gi(ctx);
    Voxelizer voxelizer(ctx);
    const Scene scene = test::quadScene({{{glm::dvec3(-5, 0, -5), {-5, 0, 5}, {5, 0, 5}, {5, 0, -5}}},
                                         {{glm::dvec3(-5, 0, -1), {5, 0, -1}, {5, 5, -1}, {-5, 5, -1}}}});
    constexpr int W = 40, H = 30;
    const GBufferView view = gbuffer.render(scene, wallCamera(W, H), {W, H, false, {}});
    for (GiMethod method : {GiMethod::Screen, GiMethod::Hybrid})
        for (AoResolution resolution : {AoResolution::Full, AoResolution::Quarter}) {
            IndirectLightSettings s;
            s.method = method;
            s.resolution = resolution;
            s.blurRadius = 2;
            if (method == GiMethod::Hybrid) s.voxels = &voxelizer.voxelize(scene, {});
            const Image radiance = readTexture(ctx, gi.run(view, s).radiance);
            for (float v : radiance.pixels) {
                CHECK(std::isfinite(v));
                CHECK(v >= 0.0f);
            }
            for (int y = 0; y < H; ++y)
                for (int x = 0; x < W; ++x)
                    for (int c = 0; c < 3; ++c) CHECK(radiance.at(x, y, c) == 0.0f);
        }
}

TEST_CASE("Indirect light stays finite for odd sizes and reversed-Z and orthographic views", "[gi][stability]") {
    test::GlFixture gl;
    Context ctx(gl.desc());
    GBuffer gbuffer(ctx);
    IndirectLight gi(ctx);
    Voxelizer voxelizer(ctx);
    const assets::LoadedScene cornell = assets::builtinScene("cornell");
    const LookAt look{{278, 273, -800}, {278, 273, 0}, {0, 1, 0}};
    // The box seen through its open side with sky around it (1 x 1: the box only); far 1000:
    // the far plane cuts through the box at z = 200 of its 0..559 and through the short block.
    for (auto [width, height, orthographic, mode, far] : {std::tuple{1, 1, false, DepthMode::Standard, 5000.0f},
                                                         std::tuple{37, 23, false, DepthMode::Reversed, 5000.0f},
                                                         std::tuple{40, 30, false, DepthMode::Reversed, INFINITY},
                                                         std::tuple{24, 31, true, DepthMode::StandardZeroToOne, 5000.0f},
                                                         std::tuple{33, 25, false, DepthMode::Standard, 1000.0f},
                                                         std::tuple{27, 29, true, DepthMode::Reversed, 1000.0f}}) {
        CAPTURE(width, height, orthographic, far);
        const float aspect = float(width) / float(height);
        const Camera camera = orthographic ? Camera::orthographic(look, 400.0f, aspect, 10.0f, far, mode)
                                           : Camera::perspective(look, glm::radians(40.0f), aspect, 10.0f, far, mode);
        GBufferSettings layers{width, height, true, {}};
        layers.depthLayers = 2; // for the peeling modes
        const GBufferView view = gbuffer.render(cornell.scene, camera, layers);
        if (far < 2000.0f) // the tall block and the back wall are cut off
            CHECK(readTexture(ctx, gbuffer.positions(view)).at(width / 2, height / 2, 3) == 0.0f);
        if (!orthographic && width * height > 100 && far > 2000.0f) {
            // The back wall faces the camera head-on: view normals of exactly (0, 0, 1), where a
            // tangent frame built by crossing with the z axis degenerates.
            const Image normals = readTexture(ctx, view.normal);
            int headOn = 0;
            for (int y = 0; y < height; ++y)
                for (int x = 0; x < width; ++x)
                    headOn += normals.at(x, y, 0) == 0.0f && normals.at(x, y, 1) == 0.0f && normals.at(x, y, 2) == 1.0f;
            CHECK(headOn > 0);
        }
        for (const auto& [method, resolution, thickness] :
             {std::tuple{GiMethod::Screen, AoResolution::Full, ScreenThickness::Constant},
              std::tuple{GiMethod::Screen, AoResolution::Half, ScreenThickness::Constant},
              std::tuple{GiMethod::Hybrid, AoResolution::Full, ScreenThickness::Constant},
              std::tuple{GiMethod::Hybrid, AoResolution::Half, ScreenThickness::Constant},
              std::tuple{GiMethod::Screen, AoResolution::Full, ScreenThickness::DepthPeeling},
              std::tuple{GiMethod::Screen, AoResolution::Half, ScreenThickness::PeelingOrConstant}}) {
            CAPTURE(method == GiMethod::Hybrid, static_cast<int>(resolution), static_cast<int>(thickness));
            auto s = test::integratorSettings<IndirectLightSettings>(150.0f, 8, IndirectLightSettings{}.steps, resolution, 1);
            s.method = method;
            s.thicknessMode = thickness;
            if (method == GiMethod::Hybrid) s.voxels = &voxelizer.voxelize(cornell.scene, {});
            const Image radiance = readTexture(ctx, gi.run(view, s).radiance);
            REQUIRE(radiance.width == width);
            for (float v : radiance.pixels) {
                CHECK(std::isfinite(v));
                CHECK(v >= 0.0f);
            }
            // Background pixels are (0, 0, 0, 0) (indirect_light.hpp).
            const Image positions = readTexture(ctx, gbuffer.positions(view));
            std::size_t sky = 0, skyNotEmpty = 0;
            for (int y = 0; y < height; ++y)
                for (int x = 0; x < width; ++x) {
                    if (positions.at(x, y, 3) > 0.0f) continue;
                    ++sky;
                    for (int c = 0; c < 4; ++c) skyNotEmpty += radiance.at(x, y, c) != 0.0f;
                }
            CHECK(skyNotEmpty == 0);
            if (width * height > 100) CHECK(sky > 0);
        }
    }
}

TEST_CASE("Post-process mode: screen-space indirect light on a host's depth layers gives the G-buffer path's light bit "
          "for bit in every thickness mode", "[gi][host]") {
    // As the AO host test: the host's buffers hold the G-buffer's values exactly (32-bit
    // float depth passes, the G-buffer's normals, albedo and lit image), so adoption must not
    // change a number; and the host's second layer must change what the peeling modes find.
    test::GlFixture gl;
    Context ctx(gl.desc());
    GBuffer gbuffer(ctx);
    IndirectLight gi(ctx);
    const assets::LoadedScene cornell = assets::builtinScene("cornell");
    constexpr int W = 40, H = 32;
    const Camera camera = test::cornellCamera(W, H);
    GBufferSettings layers{W, H, true, {}};
    layers.depthLayers = 2;
    const GBufferView view = gbuffer.render(cornell.scene, camera, layers);
    const GLuint depth = test::copyDepthAsHost(view.depth.name, W, H, GL_DEPTH_COMPONENT32F);
    const GLuint back = test::copyDepthAsHost(view.backDepth.name, W, H, GL_DEPTH_COMPONENT32F);
    HostGBuffer host;
    host.depth = {depth, 0, 0, 0};
    host.backDepth = {back, 0, 0, 0};
    host.normal = view.normal;
    host.albedo = view.albedo;
    host.directRadiance = view.directRadiance;
    GBuffer adopter(ctx);
    GBufferView adopted = adopter.adopt(host, camera);
    REQUIRE(adopted.backDepth.name == back);
    adopted.normalError = view.normalError; // the G-buffer's normals, rounded once (see the AO test)
    for (const ScreenMarch march : {ScreenMarch::View, ScreenMarch::Texture, ScreenMarch::HiZ})
        for (const AoResolution resolution : {AoResolution::Full, AoResolution::Half}) {
            std::vector<float> constant;
            for (const ScreenThickness mode :
                 {ScreenThickness::Constant, ScreenThickness::DepthPeeling, ScreenThickness::PeelingOrConstant}) {
                CAPTURE(static_cast<int>(march), static_cast<int>(resolution), static_cast<int>(mode));
                IndirectLightSettings s;
                s.march = march;
                s.thicknessMode = mode;
                // A slab below the blocks' size, so that the union differs from the constant.
                if (mode == ScreenThickness::PeelingOrConstant) s.thickness = 15.0f;
                s.radius = 150.0f;
                s.rays = 16;
                s.resolution = resolution;
                s.blurRadius = resolution == AoResolution::Full ? 0 : 2;
                const Image own = readTexture(ctx, gi.run(view, s).radiance);
                const Image post = readTexture(ctx, gi.run(adopted, s).radiance);
                int lit = 0; // colour channels with light (alpha is 1 on every geometry pixel)
                for (std::size_t i = 0; i < own.pixels.size(); ++i) lit += i % 4 != 3 && own.pixels[i] > 0.0f;
                CHECK(lit > W * H); // a third of the 3 W H (16 rays light about half)
                CHECK(post.pixels == own.pixels);
                if (mode == ScreenThickness::Constant) constant = own.pixels;
                else CHECK(post.pixels != constant);
            }
        }
    glDeleteTextures(1, &depth);
    glDeleteTextures(1, &back);
    CHECK(test::drainGlErrors().empty());
}

TEST_CASE("Hybrid indirect light with a radius far past the grid gathers what a radius just past it gathers",
          "[gi][stability]") {
    // As for voxel AO (test_ao_screen_voxel.cpp): radius 1e3 ends rays 3.2e4 voxels out, within
    // the traversals' coordinate limit, 1e9 past it, where rays were refused whole (no light
    // at all) before they were shortened to half the limit. Past the grid nothing is hit, so
    // both gather the same light, but a hit's distance is its segment parameter times the
    // ray's reach, and the two reaches round the hit point differently (float rounding, the
    // segment's end snapped to the traversal's 1/4096-voxel grid): a hit near a pixel border
    // may be read from the neighbouring pixel. So the frame's total light must agree within
    // 1 %, one ray in a hundred landing in another pixel, far more than that rounding moves.
    WallLight f;
    auto& [gl, ctx, gbuffer, voxelizer, gi, scene] = f;
    constexpr int W = 48, H = 36;
    const GBufferView view = gbuffer.render(scene, wallCamera(W, H), {W, H, false, {}});
    IndirectLightSettings s;
    s.method = GiMethod::Hybrid;
    s.rays = 64;
    s.voxels = &voxelizer.voxelize(scene, test::wallVoxels());
    const auto total = [](const Image& radiance, int& lit) {
        double sum = 0.0;
        lit = 0;
        for (int y = 0; y < radiance.height; ++y)
            for (int x = 0; x < radiance.width; ++x) {
                lit += radiance.at(x, y, 0) > 0.0f;
                for (int c = 0; c < 3; ++c) sum += radiance.at(x, y, c);
            }
        return sum;
    };
    for (const VoxelTraversal traversal : {VoxelTraversal::Exact, VoxelTraversal::Hierarchical}) {
        CAPTURE(static_cast<int>(traversal));
        s.voxelTraversal = traversal;
        s.radius = 1e3f;
        int lit = 0, farLit = 0;
        const double near = total(readTexture(ctx, gi.run(view, s).radiance), lit);
        s.radius = 1e9f;
        const double far = total(readTexture(ctx, gi.run(view, s).radiance), farLit);
        CAPTURE(near, far, lit, farLit);
        CHECK(lit > W * H / 8); // the floor before the wall
        CHECK(std::abs(far - near) <= 0.01 * near);
    }
}

TEST_CASE("Indirect light with a projection mirrored in y, a GL_UPPER_LEFT host's, is the unmirrored light mirrored",
          "[gi][host]") {
    // As for AO (test_ao_host.cpp): with the projection's row 1 negated, the rows run top down
    // and every method must gather what the unmirrored camera's do, in mirrored rows, as
    // noisy as checkMirroredLikeBaselines allows. The G-buffer is rendered with the mirrored
    // projection (its depth is a GL_UPPER_LEFT host's, test_ao_host.cpp; adoption gives the
    // G-buffer path's light bit for bit, test_host_lighting.cpp), lit by the box's light.
    test::GlFixture gl;
    Context ctx(gl.desc());
    GBuffer gbuffer(ctx), shiftedGBuffer(ctx), mirroredGBuffer(ctx);
    IndirectLight gi(ctx);
    Voxelizer voxelizer(ctx);
    const assets::LoadedScene cornell = assets::builtinScene("cornell");
    constexpr int W = 48, H = 40;
    const Camera camera = test::cornellCamera(W, H);
    const GBufferSettings lit{W, H, true, {}};
    const GBufferView view = gbuffer.render(cornell.scene, camera, lit);
    const GBufferView shifted = shiftedGBuffer.render(cornell.scene, test::shiftedOnePixel(camera, W), lit);
    const GBufferView mirrored = mirroredGBuffer.render(cornell.scene, test::mirrored(camera, 1), lit);
    const Image positions = readTexture(ctx, gbuffer.positions(view));
    const Image shiftedPositions = readTexture(ctx, shiftedGBuffer.positions(shifted));
    const VoxelGrid& voxels = voxelizer.voxelize(cornell.scene, {});
    for (const GiMethod method : {GiMethod::Screen, GiMethod::Hybrid}) {
        CAPTURE(static_cast<int>(method));
        IndirectLightSettings s;
        s.method = method;
        s.radius = 300.0f;
        s.rays = 32;
        if (method == GiMethod::Hybrid) s.voxels = &voxels;
        const Image full = readTexture(ctx, gi.run(view, s).radiance);
        const Image shiftedFull = readTexture(ctx, gi.run(shifted, s).radiance);
        const Image mirroredFull = readTexture(ctx, gi.run(mirrored, s).radiance);
        s.resolution = AoResolution::Half;
        s.blurRadius = 2;
        const Image half = readTexture(ctx, gi.run(view, s).radiance);
        const Image mirroredHalf = readTexture(ctx, gi.run(mirrored, s).radiance);
        int litPixels = 0;
        for (std::size_t i = 0; i < full.pixels.size(); i += 4) litPixels += full.pixels[i] > 0.0f;
        CHECK(litPixels > W * H / 4); // nothing gathered would prove nothing
        test::checkMirroredLikeBaselines(
            test::mirroredDifferences(positions, shiftedPositions, 3, full, mirroredFull, shiftedFull, half, mirroredHalf));
    }
    CHECK(test::drainGlErrors().empty());
}

TEST_CASE("Indirect light refuses bad settings and buffers without radiance", "[gi][bad-input]") {
    test::GlFixture gl;
    Context ctx(gl.desc());
    GBuffer gbuffer(ctx);
    IndirectLight gi(ctx);
    const Scene scene = test::quadScene({{{glm::dvec3(-5, 0, -5), {-5, 0, 5}, {5, 0, 5}, {5, 0, -5}}}});
    const GBufferView view = gbuffer.render(scene, wallCamera(16, 16), {16, 16, true, {}});
    for (auto change : std::vector<void (*)(IndirectLightSettings&)>{
             [](IndirectLightSettings& s) { s.radius = -1.0f; }, [](IndirectLightSettings& s) { s.rays = 0; },
             [](IndirectLightSettings& s) { s.steps = 300; }, [](IndirectLightSettings& s) { s.blurRadius = -1; },
             [](IndirectLightSettings& s) { s.refineThreshold = 1.5f; },
             [](IndirectLightSettings& s) { s.rayLanes = 6; }, [](IndirectLightSettings& s) { s.rayLanes = -1; },
             [](IndirectLightSettings& s) { s.method = GiMethod::Hybrid; },
             [](IndirectLightSettings& s) { s.method = static_cast<GiMethod>(2); },
             [](IndirectLightSettings& s) { s.resolution = static_cast<AoResolution>(0); },
             [](IndirectLightSettings& s) { s.resolution = static_cast<AoResolution>(8); },
             [](IndirectLightSettings& s) { s.march = static_cast<ScreenMarch>(-1); },
             [](IndirectLightSettings& s) { s.thicknessMode = static_cast<ScreenThickness>(5); }}) {
        IndirectLightSettings s;
        change(s);
        CHECK_THROWS_AS(gi.run(view, s), Error);
    }
    HostGBuffer host;
    host.depth = view.depth;
    const GBufferView adopted = gbuffer.adopt(host, view.camera);
    CHECK_THROWS_AS(gi.run(adopted, {}), Error);
    CHECK(test::drainGlErrors().empty());
}
