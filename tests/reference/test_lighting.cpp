// Direct, indirect, shadow and image-based lighting against closed forms.
#include "obscura/assets.hpp"
#include "obscura/error.hpp"
#include "reference_helpers.hpp"

#include <catch2/catch.hpp>

#include <filesystem>

using namespace obscura;
using namespace obscura::reference;
using test::kPi;

namespace {

const test::QuadCorners kFloor{{{-50, 0, -50}, {-50, 0, 50}, {50, 0, 50}, {50, 0, -50}}};

// The estimate's own noise, from the halves: the MSE of `value` is about noiseMse.
double sigmaOf(const Reference& r) { return std::sqrt(r.noiseMse); }

std::filesystem::path writeUniformEnvironment(float radiance) {
    Image img;
    img.width = 8;
    img.height = 4;
    img.channels = 3;
    img.pixels.assign(8 * 4 * 3, radiance);
    const auto path = std::filesystem::temp_directory_path() / "obscura_uniform_env.exr";
    assets::writeImage(path, img);
    return path;
}

double cornerViewFactor(double a, double b) {
    const double sa = std::sqrt(1 + a * a), sb = std::sqrt(1 + b * b);
    return (a / sa * std::atan(b / sa) + b / sb * std::atan(a / sb)) / (2 * kPi);
}

} // namespace

TEST_CASE("White furnace - a uniform environment gives irradiance pi L", "[reference][ibl]") {
    const float radiance = 1.7f;
    Scene s = test::meshScene({test::quadMesh(kFloor)});
    s.environment = Environment{writeUniformEnvironment(radiance).string(), 1.0f, 0.3f};
    const RayScene scene(s);
    std::vector<glm::dvec3> at;
    for (int i = 0; i < 32; ++i) at.emplace_back(0.1 * i, 0, -0.05 * i);
    RenderSettings settings;
    settings.samplesPerPixel = 1024;
    const Reference r = render(scene, test::pointsAt(at, {0, 1, 0}), ImageBasedLight{true, true}, settings);
    const double expected = kPi * radiance;
    for (int c = 0; c < 3; ++c) {
        const test::Stats st = test::stats(r.value, c);
        // The mean over 32 independent pixels, within 4 standard errors.
        CHECK(std::abs(st.mean - expected) < 4 * st.stddev / std::sqrt(double(st.n)) + 1e-12 * expected);
    }
    for (float v : r.value.pixels) CHECK(std::abs(v - expected) < 6 * sigmaOf(r) + 1e-9);
    // Outgoing radiance of a white Lambertian surface in the furnace is L again.
    const Reference out = render(scene, test::pointsAt(at, {0, 1, 0}), ImageBasedLight{false, true}, settings);
    CHECK(test::stats(out.value, 0).mean == Approx(radiance).epsilon(0.01));
}

TEST_CASE("A real HDR environment - irradiance of an upward plane equals the texel sum", "[reference][ibl]") {
    const std::filesystem::path file = std::filesystem::path(OBSCURA_BLENDER_WORLDS) / "forest.exr";
    REQUIRE(std::filesystem::exists(file)); // scripts/setup-debian.sh installs blender-data
    const Image env = assets::readImage(file);
    // The exact irradiance of the piecewise-constant (nearest-texel) environment on a plane
    // facing +y: each texel row [theta0, theta1] above the horizon contributes
    // L dphi (sin^2 theta1 - sin^2 theta0) / 2. Negative texels (lossy compression) count as 0.
    glm::dvec3 expected(0.0);
    for (int y = 0; y < env.height; ++y) {
        const double t0 = kPi * y / env.height, t1 = std::min(kPi * (y + 1) / env.height, kPi / 2);
        if (t0 >= kPi / 2) break;
        for (int x = 0; x < env.width; ++x)
            for (int c = 0; c < 3; ++c)
                expected[c] += std::max(0.0f, env.at(x, y, std::min(c, env.channels - 1))) * (2 * kPi / env.width) *
                               (std::sin(t1) * std::sin(t1) - std::sin(t0) * std::sin(t0)) / 2;
    }
    Scene s = test::meshScene({test::quadMesh(kFloor)});
    s.environment = Environment{file.string(), 1.0f, 0.0f};
    const RayScene scene(s);
    std::vector<glm::dvec3> at(48, glm::dvec3(0.0));
    RenderSettings settings;
    settings.samplesPerPixel = 512;
    const Reference r = render(scene, test::pointsAt(at, {0, 1, 0}), ImageBasedLight{true, true}, settings);
    for (int c = 0; c < 3; ++c) {
        const test::Stats st = test::stats(r.value, c);
        INFO("channel " << c << ": " << st.mean << " vs " << expected[c] << " (stddev " << st.stddev << ")");
        CHECK(std::abs(st.mean - expected[c]) < 4 * st.stddev / std::sqrt(double(st.n)));
    }
}

TEST_CASE("Direct light from a rectangle and a sphere matches closed forms without occluders", "[reference][direct]") {
    for (bool rect : {true, false}) {
        Scene s = test::meshScene({test::quadMesh(kFloor)}, glm::vec3(0.5f));
        Light l;
        l.intensity = 2.0f;
        if (rect) {
            l.type = LightType::Rect;
            l.position = {0, 1.0f, 0};
            l.direction = {0, -1, 0};
            l.size = {1.2f, 0.8f};
        } else {
            l.type = LightType::Sphere;
            l.position = {0, 1.0f, 0};
            l.radius = 0.3f;
        }
        s.lights.push_back(l);
        const RayScene scene(s);
        std::vector<glm::dvec3> at(32, glm::dvec3(0.0));
        RenderSettings settings;
        settings.samplesPerPixel = 1024;
        const Reference r = render(scene, test::pointsAt(at, {0, 1, 0}, glm::dvec3(0.5)), DirectLight{true}, settings);
        // Rect centred above: 4 corner rectangles 0.6 x 0.4 at height 1, E = pi L F.
        // Sphere fully above the horizon: E = pi r^2 L / d^2.
        const double e = rect ? kPi * 2.0 * 4 * cornerViewFactor(0.6, 0.4) : kPi * 0.09 * 2.0;
        const double expected = 0.5 / kPi * e;
        const test::Stats st = test::stats(r.value, 0);
        INFO((rect ? "rect" : "sphere") << ": " << st.mean << " vs " << expected);
        // The mean over 32 independent pixels, within 4 standard errors.
        CHECK(std::abs(st.mean - expected) < 4 * st.stddev / std::sqrt(double(st.n)) + 1e-12);
    }
}

TEST_CASE("Indirect light under an emissive disc is albedo times emission times the view factor", "[reference][indirect]") {
    const double h = 1.0, a = 0.5, emitted = 3.0, albedo = 0.6;
    Scene s = test::meshScene({test::quadMesh(kFloor)});
    Material lamp;
    lamp.albedo = glm::vec3(0.0f);
    lamp.emission = glm::vec3(static_cast<float>(emitted));
    s.materials.push_back(lamp);
    s.meshes.push_back({test::discMesh({0, h, 0}, a, 1024), glm::mat4(1.0f), 1, "lamp"});
    const RayScene scene(s);
    std::vector<glm::dvec3> at(32, glm::dvec3(0.0));
    RenderSettings settings;
    settings.samplesPerPixel = 1024;
    const Reference r = render(scene, test::pointsAt(at, {0, 1, 0}, glm::dvec3(albedo)), IndirectLight{}, settings);
    const double expected = albedo * emitted * a * a / (h * h + a * a);
    const test::Stats st = test::stats(r.value, 0);
    CHECK(std::abs(st.mean - expected) < 4 * st.stddev / std::sqrt(double(st.n)));
    // The near field of radius < h contains nothing.
    const Reference near = render(scene, test::pointsAt(at, {0, 1, 0}, glm::dvec3(albedo)), IndirectLight{0.9 * h}, settings);
    for (float v : near.value.pixels) CHECK(v == 0.0f);
}

TEST_CASE("A hard shadow mask follows the occluder's projection", "[reference][shadow]") {
    // A point light at height 2 above the origin, a disc of radius 0.5 at height 1: the umbra
    // on the floor is the disc's projection, radius 1.
    Scene s = test::meshScene({test::quadMesh(kFloor), test::discMesh({0, 1, 0}, 0.5, 256)});
    Light l;
    l.position = {0, 2, 0};
    s.lights.push_back(l);
    const RayScene scene(s);
    const ShadingPoints points = test::pointsAt({{0, 0, 0}, {0.9, 0, 0}, {0, 0, -0.95}, {1.1, 0, 0}, {0, 0, 1.5}}, {0, 1, 0});
    RenderSettings settings;
    settings.samplesPerPixel = 2;
    const Reference r = render(scene, points, Shadow{0}, settings);
    const float expected[5] = {0, 0, 0, 1, 1};
    for (int i = 0; i < 5; ++i) {
        CHECK(r.value.pixels[static_cast<std::size_t>(i) * 2] == expected[i]);
        CHECK(r.value.pixels[static_cast<std::size_t>(i) * 2 + 1] == 1.0f); // every point faces the light
    }
    CHECK(r.noiseMse == 0.0); // a hard light is exact
    CHECK_THROWS_AS(render(scene, points, Shadow{3}, settings), Error);
}
