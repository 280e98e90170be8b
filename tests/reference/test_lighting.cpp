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

TEST_CASE("Materials emit from their front side only", "[reference][indirect]") {
    // The disc of the test above turned over (its triangles wound the other way): the floor
    // under it sees its back, which emits nothing; a camera below sees the front emit, one
    // above the back (its albedo is 0, so what the back shows is 0 too).
    const double h = 1.0, a = 0.5, emitted = 3.0;
    auto flipped = std::make_shared<MeshData>(*test::discMesh({0, h, 0}, a, 64));
    for (std::size_t i = 0; i + 2 < flipped->indices.size(); i += 3) std::swap(flipped->indices[i + 1], flipped->indices[i + 2]);
    Material lamp;
    lamp.albedo = glm::vec3(0.0f);
    lamp.emission = glm::vec3(static_cast<float>(emitted));
    for (const bool turned : {false, true}) {
        CAPTURE(turned);
        Scene s = test::meshScene({test::quadMesh(kFloor)});
        s.materials.push_back(lamp);
        s.meshes.push_back({turned ? flipped : test::discMesh({0, h, 0}, a, 64), glm::mat4(1.0f), 1, "lamp"});
        const RayScene scene(s);
        RenderSettings settings;
        settings.samplesPerPixel = 256;
        const Reference r = render(scene, test::pointsAt(std::vector<glm::dvec3>(8, glm::dvec3(0.0)), {0, 1, 0}, glm::dvec3(0.6)),
                                   IndirectLight{}, settings);
        const test::Stats st = test::stats(r.value, 0);
        if (turned) CHECK(st.mean == 0.0);
        else CHECK(st.mean > 0.1); // 0.6 * 3 * a^2 / (h^2 + a^2) = 0.36 (the test above)
        for (const double eyeY : {0.5, 2.0}) {
            const Camera camera = Camera::perspective({{0, float(eyeY), 0.01f}, {0, float(h), 0}, {0, 0, 1}}, 0.3f, 1.0f, 0.01f, 10.0f);
            const ShadingPoints points = fromCamera(scene, camera, 4, 4);
            const bool seesFront = (eyeY < h) != turned;
            for (const ShadingPoint& p : points.points) {
                REQUIRE(p.surface());
                CHECK(p.emission.x == (seesFront ? emitted : 0.0));
            }
        }
    }
}

TEST_CASE("Indirect light gathers shadowed or unshadowed direct light at its hits", "[reference][indirect]") {
    // The sun straight down, a roof at height 3 over the whole floor: the floor is in shadow.
    // A point facing +x just above the floor sees the floor in the lower half of its
    // cosine-weighted hemisphere, less the band within atan(h / 50) under the horizon that
    // passes the floor's edge (a share of at most (2 / pi) atan(h / 50), about 1e-4), and
    // the roof's underside, which faces away from the sun, in the upper half.
    constexpr double h = 0.01, floorAlbedo = 0.5, albedo = 0.6, irradiance = 2.0;
    Scene s = test::meshScene({test::quadMesh(kFloor),
                               test::quadMesh({{{-50, 3, -50}, {50, 3, -50}, {50, 3, 50}, {-50, 3, 50}}})},
                              glm::vec3(static_cast<float>(floorAlbedo)));
    Light sun;
    sun.type = LightType::Directional;
    sun.direction = {0, -1, 0};
    sun.intensity = static_cast<float>(irradiance);
    s.lights.push_back(sun);
    const RayScene scene(s);
    const std::vector<glm::dvec3> at(32, glm::dvec3(0.0, h, 0.0));
    const ShadingPoints points = test::pointsAt(at, {1, 0, 0}, glm::dvec3(albedo));
    RenderSettings settings;
    settings.samplesPerPixel = 1024;
    const Reference shadowed = render(scene, points, IndirectLight{}, settings);
    for (float v : shadowed.value.pixels) CHECK(v == 0.0f);
    IndirectLight unshadowed;
    unshadowed.directVisibility = false;
    const Reference r = render(scene, points, unshadowed, settings);
    const double floorRadiance = albedo * floorAlbedo / kPi * irradiance, missing = 2.0 / kPi * std::atan(h / 50.0);
    const double hi = floorRadiance * 0.5, lo = floorRadiance * (0.5 - missing);
    const test::Stats st = test::stats(r.value, 0);
    INFO(st.mean << " vs [" << lo << ", " << hi << "]");
    const double tolerance = 4 * st.stddev / std::sqrt(double(st.n));
    CHECK(st.mean >= lo - tolerance);
    CHECK(st.mean <= hi + tolerance);
    CHECK(describe(unshadowed) != describe(IndirectLight{}));
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

TEST_CASE("Point spot and directional light match Lambert's law with the shading normal", "[reference][direct]") {
    // Vertex normals tilted by 0.3 rad about z: the receiver's cosine uses them (as the
    // G-buffer does), the horizon the geometric normal.
    auto floor = test::quadMesh(kFloor);
    const glm::dvec3 tilted(std::sin(0.3), std::cos(0.3), 0.0);
    floor->normals.assign(4, glm::vec3(tilted));
    Scene s = test::meshScene({floor}, glm::vec3(0.8f));
    const auto kind = GENERATE(0, 1, 2);
    Light l;
    l.intensity = 2.0f;
    l.color = {1.0f, 0.5f, 0.25f};
    if (kind == 2) {
        l.type = LightType::Directional;
        l.direction = glm::normalize(glm::vec3(-0.2f, -1.0f, 0.3f));
    } else {
        l.type = kind == 0 ? LightType::Point : LightType::Spot;
        l.position = {0.3f, 1.5f, -0.2f};
        l.direction = {0, -1, 0};
        l.innerAngle = 0.2f;
        l.outerAngle = 0.5f;
    }
    s.lights.push_back(l);
    const RayScene scene(s);
    std::vector<glm::dvec3> at = {{0, 0, 0}, {0.5, 0, 0.3}, {-0.4, 0, -0.6}, {1.5, 0, 1.0}};
    reference::ShadingPoints points = test::pointsAt(at, {0, 1, 0}, glm::dvec3(0.8));
    for (auto& p : points.points) p.shadingNormal = tilted;
    RenderSettings settings;
    settings.samplesPerPixel = 2;
    const Reference r = render(scene, points, DirectLight{true}, settings);
    for (std::size_t i = 0; i < at.size(); ++i) {
        double e;
        if (kind == 2) {
            e = l.intensity * std::max(0.0, glm::dot(tilted, -glm::dvec3(l.direction)));
        } else {
            const glm::dvec3 d = glm::dvec3(l.position) - at[i];
            const glm::dvec3 w = glm::normalize(d);
            e = l.intensity * std::max(0.0, glm::dot(tilted, w)) / glm::dot(d, d);
            if (kind == 1) {
                const double c = w.y, c0 = std::cos(0.5), c1 = std::cos(0.2); // dot(-w, -y)
                const double t = std::clamp((c - c0) / (c1 - c0), 0.0, 1.0);
                e *= t * t * (3 - 2 * t);
            }
        }
        for (int c = 0; c < 3; ++c)
            CHECK(r.value.pixels[i * 3 + static_cast<std::size_t>(c)] == Approx(0.8 / kPi * e * l.color[c]).epsilon(1e-6));
    }
    CHECK(r.noiseMse == 0.0); // hard lights are exact
}

TEST_CASE("A half-plane occluder hides exactly half of a rectangular light", "[reference][shadow]") {
    // Rect light centred above the origin at height 2; a half-plane x < 0 at height 1. From
    // points on the x = 0 line every ray to the light's x < 0 half crosses the plate, and no
    // ray to the x > 0 half does; the light is symmetric in x, so half the irradiance arrives.
    Scene s = test::meshScene({test::quadMesh(kFloor),
                               test::quadMesh({{{-50, 1, -50}, {0, 1, -50}, {0, 1, 50}, {-50, 1, 50}}})});
    Light l;
    l.type = LightType::Rect;
    l.position = {0, 2, 0};
    l.direction = {0, -1, 0};
    l.size = {1.0f, 0.6f};
    s.lights.push_back(l);
    const RayScene scene(s);
    std::vector<glm::dvec3> at = {{0, 0, 0}, {0, 0, 0.2}, {0, 0, -0.35}};
    RenderSettings settings;
    settings.samplesPerPixel = 8192;
    const Reference r = render(scene, test::pointsAt(at, {0, 1, 0}), Shadow{0}, settings);
    // Each half is a ratio of two means over n/2 samples; the visible fraction of a sample is
    // 0 or 1, so its sampling error is at most 1/(2 sqrt(n/2)) per half: 4 of those, over both.
    const double tolerance = 4 * 0.5 / std::sqrt(settings.samplesPerPixel / 2.0) / std::sqrt(2.0);
    for (std::size_t i = 0; i < at.size(); ++i) {
        CHECK(std::abs(r.value.pixels[i * 2] - 0.5) < tolerance);
        CHECK(r.value.pixels[i * 2 + 1] == 1.0f);
    }
}

TEST_CASE("Indirect light sampling area lights converges as the samples grow", "[reference][indirect]") {
    // A floor and a wall lit by a rect light: the bounce needs a direction and a light sample
    // per sample; if the two were tied together the error would stop shrinking.
    Scene s = test::meshScene({test::quadMesh(kFloor), test::quadMesh({{{-5, 0, -1}, {5, 0, -1}, {5, 5, -1}, {-5, 5, -1}}})},
                              glm::vec3(0.7f));
    Light l;
    l.type = LightType::Rect;
    l.position = {0, 1.0f, 0.5f};
    l.direction = {0, 0, -1};
    l.size = {1.0f, 1.0f};
    l.intensity = 5.0f;
    s.lights.push_back(l);
    const RayScene scene(s);
    std::vector<glm::dvec3> at;
    for (int i = 0; i < 16; ++i) at.emplace_back(-0.4 + 0.05 * i, 0, 0.2);
    const auto noiseAt = [&](int spp) {
        RenderSettings settings;
        settings.samplesPerPixel = spp;
        return render(scene, test::pointsAt(at, {0, 1, 0}, glm::dvec3(0.7)), IndirectLight{}, settings).noiseMse;
    };
    const double coarse = noiseAt(256), fine = noiseAt(4096);
    INFO("noise MSE " << coarse << " at 256 spp, " << fine << " at 4096 spp");
    // Independent samples: MSE ~ 1/n, so 16x fewer; allow a factor 2 for the spread of the
    // estimates over 16 pixels.
    CHECK(fine < coarse / 8);
}

TEST_CASE("The environment's azimuth and rotation follow the documented convention", "[reference][ibl]") {
    // An environment bright only where the documented mapping puts +x (u = 0.75 is phi =
    // pi/2: direction (sin theta, cos theta, 0) at the equator), dark elsewhere.
    Image img;
    img.width = 64;
    img.height = 32;
    img.channels = 3;
    img.pixels.assign(64 * 32 * 3, 0.0f);
    for (int y = 0; y < 32; ++y)
        for (int x = 40; x < 56; ++x) // u in [0.625, 0.875): phi in [pi/4, 3 pi/4], around +x
            for (int c = 0; c < 3; ++c) img.at(x, y, c) = 1.0f;
    const auto path = std::filesystem::temp_directory_path() / "obscura_quadrant_env.exr";
    assets::writeImage(path, img);
    Scene s = test::meshScene({});
    s.materials[0].albedo = glm::vec3(1.0f);
    for (float rotation : {0.0f, float(kPi)}) {
        s.environment = Environment{path.string(), 1.0f, rotation};
        const RayScene scene(s);
        RenderSettings settings;
        settings.samplesPerPixel = 1024;
        // 16 points facing +x, then 16 facing -x, nothing around them.
        reference::ShadingPoints pts = test::pointsAt(std::vector<glm::dvec3>(16, glm::dvec3(0.0)), {1, 0, 0});
        const auto facingMinus = test::pointsAt(std::vector<glm::dvec3>(16, glm::dvec3(0.0)), {-1, 0, 0});
        pts.points.insert(pts.points.end(), facingMinus.points.begin(), facingMinus.points.end());
        pts.width = 32;
        const Reference r = render(scene, pts, ImageBasedLight{true, false}, settings);
        // The bright band spans phi in [pi/4, 3 pi/4]: its cosine-weighted irradiance on a
        // surface facing its centre is Int cos = Int_0^pi sin^2 theta dtheta * Int cos(phi - pi/2) dphi
        // = (pi/2) * 2 sin(pi/4) = pi / sqrt(2).
        const double expected = kPi / std::sqrt(2.0);
        Image plus = r.value, minus = r.value;
        plus.width = minus.width = 16;
        plus.pixels.assign(r.value.pixels.begin(), r.value.pixels.begin() + 48);
        minus.pixels.assign(r.value.pixels.begin() + 48, r.value.pixels.end());
        const test::Stats lit = test::stats(rotation == 0.0f ? plus : minus, 0);
        const test::Stats dark = test::stats(rotation == 0.0f ? minus : plus, 0);
        CAPTURE(rotation, lit.mean, dark.mean);
        CHECK(std::abs(lit.mean - expected) < 4 * lit.stddev / std::sqrt(double(lit.n)) + 1e-9);
        CHECK(dark.mean < 0.01 * expected);
    }
}
