// One-bounce indirect light: a closed form (a floor lit by an emissive wall), zero where
// nothing is lit, stability, and the inputs it refuses.
#include "gl_fixture.hpp"
#include "scene_builders.hpp"

#include "obscura/assets.hpp"
#include "obscura/obscura.hpp"

#include <catch2/catch.hpp>

#include <cmath>

using namespace obscura;

namespace {

constexpr double kPi = 3.14159265358979323846;

// As in test_ambient_occlusion.cpp: the share of cosine-weighted directions from a floor
// point at distance D from an infinite wall that reach the wall within r.
double wallShare(double distance, double radius) {
    const double c = distance / radius;
    if (c >= 1.0) return 0.0;
    return (std::acos(c) - c * std::sqrt(1.0 - c * c)) / kPi;
}

Camera wallCamera(int width, int height) {
    return Camera::perspective({{0, 2.5f, 3.5f}, {0, 0.3f, -0.6f}, {0, 1, 0}}, glm::radians(50.0f),
                               float(width) / float(height), 0.05f, 200.0f);
}

} // namespace

TEST_CASE("A floor lit by an emissive wall matches the closed form within the sampling error", "[gi]") {
    test::GlFixture gl;
    Context ctx(gl.desc());
    GBuffer gbuffer(ctx);
    Voxelizer voxelizer(ctx);
    IndirectLight gi(ctx);
    // Grey floor, and the wall z = -1 emitting Le toward the floor (its own albedo plays no
    // part: one bounce).
    Scene scene = test::quadScene({{{glm::dvec3(-20, 0, -20), {-20, 0, 20}, {20, 0, 20}, {20, 0, -20}}},
                                   {{glm::dvec3(-20, 0, -1), {20, 0, -1}, {20, 20, -1}, {-20, 20, -1}}}});
    const glm::vec3 emission(2.0f, 1.0f, 0.5f);
    Material wall;
    wall.albedo = glm::vec3(0.0f);
    wall.emission = emission;
    scene.materials.push_back(wall);
    scene.meshes[1].material = 1;
    constexpr int W = 96, H = 72;
    const GBufferView view = gbuffer.render(scene, wallCamera(W, H), {W, H, false, {}});
    const Image positions = readTexture(ctx, gbuffer.positions(view));
    const Image albedo = readTexture(ctx, view.albedo);
    const glm::dmat4 toWorld = glm::inverse(glm::dmat4(view.camera.view));
    constexpr double radius = 1.0;
    constexpr int rays = 1024, steps = 32;
    VoxelizerSettings voxels;
    voxels.resolution = 128;
    voxels.fitBox = false;
    voxels.boxMin = glm::vec3(-2.0f, -0.5f, -1.5f);
    voxels.boxMax = glm::vec3(2.0f, 3.5f, 2.5f);
    const double voxelSide = 4.0 / 128.0;
    for (GiMethod method : {GiMethod::Screen, GiMethod::Hybrid}) {
        CAPTURE(method == GiMethod::Hybrid);
        IndirectLightSettings s;
        s.method = method;
        s.radius = static_cast<float>(radius);
        s.rays = rays;
        s.steps = steps;
        if (method == GiMethod::Hybrid) s.voxels = &voxelizer.voxelize(scene, voxels);
        const Image radiance = readTexture(ctx, gi.run(view, s).radiance);
        int checked = 0;
        for (int y = 10; y < H; ++y)
            for (int x = 12; x < W - 12; ++x) {
                if (positions.at(x, y, 3) == 0.0f) continue;
                const glm::dvec3 p = glm::dvec3(toWorld * glm::dvec4(positions.at(x, y, 0), positions.at(x, y, 1),
                                                                      positions.at(x, y, 2), 1.0));
                if (std::abs(p.y) > 1e-3 || std::abs(p.x) > 0.8 || p.z > 1.2) continue;
                const double distance = p.z + 1.0;
                // L1 = rho Le (share of directions reaching the wall within r): as for AO,
                // marching misses hits beyond its last sample, voxels bring the wall closer.
                double lo = wallShare(distance, radius), hi = lo;
                if (method == GiMethod::Screen) lo = wallShare(distance, radius * (1.0 - 1.0 / steps));
                else hi = wallShare(std::max(distance - voxelSide, 0.0), radius);
                const double sigma = std::sqrt(std::max({lo * (1.0 - lo), hi * (1.0 - hi), 1.0 / rays}) / rays);
                for (int c = 0; c < 3; ++c) {
                    const double scale = albedo.at(x, y, c) * emission[c];
                    // 5 sigma of the share, and the 16-bit float output (2^-11 relative).
                    const double tolerance = scale * 5.0 * sigma + std::ldexp(scale, -11);
                    const double value = radiance.at(x, y, c);
                    CAPTURE(x, y, c, distance, value, scale * lo, scale * hi);
                    CHECK(value >= scale * lo - tolerance);
                    CHECK(value <= scale * hi + tolerance);
                }
                CHECK(radiance.at(x, y, 3) == 1.0f);
                ++checked;
            }
        CHECK(checked > 200);
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
    for (auto [width, height, orthographic, mode] : {std::tuple{1, 1, false, DepthMode::Standard},
                                                    std::tuple{37, 23, false, DepthMode::Reversed},
                                                    std::tuple{24, 31, true, DepthMode::StandardZeroToOne}}) {
        CAPTURE(width, height, orthographic);
        const float aspect = float(width) / float(height);
        const Camera camera = orthographic ? Camera::orthographic(look, 400.0f, aspect, 10.0f, 5000.0f, mode)
                                           : Camera::perspective(look, glm::radians(40.0f), aspect, 10.0f, 5000.0f, mode);
        const GBufferView view = gbuffer.render(cornell.scene, camera, {width, height, true, {}});
        for (GiMethod method : {GiMethod::Screen, GiMethod::Hybrid}) {
            IndirectLightSettings s;
            s.method = method;
            s.radius = 150.0f;
            s.rays = 8;
            s.resolution = AoResolution::Half;
            s.blurRadius = 1;
            if (method == GiMethod::Hybrid) s.voxels = &voxelizer.voxelize(cornell.scene, {});
            const Image radiance = readTexture(ctx, gi.run(view, s).radiance);
            REQUIRE(radiance.width == width);
            for (float v : radiance.pixels) {
                CHECK(std::isfinite(v));
                CHECK(v >= 0.0f);
            }
        }
    }
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
             [](IndirectLightSettings& s) { s.method = GiMethod::Hybrid; }}) {
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
