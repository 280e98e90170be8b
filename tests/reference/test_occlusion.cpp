// Ambient occlusion, obscurance and bent normals against closed forms.
#include "obscura/assets.hpp"
#include "reference_helpers.hpp"

#include <catch2/catch.hpp>

using namespace obscura;
using namespace obscura::reference;
using test::kPi;

namespace {
const test::QuadCorners kFloor{{{-50, 0, -50}, {-50, 0, 50}, {50, 0, 50}, {50, 0, -50}}};
std::vector<glm::dvec3> pointsNearCentre() { return {{0, 0, 0}, {0.01, 0, -0.02}, {-0.015, 0, 0.005}}; }
} // namespace

TEST_CASE("AO of an unoccluded plane is 1", "[reference][ao]") {
    const RayScene scene(test::meshScene({test::quadMesh(kFloor)}));
    // The built-in plane seen from its camera, and points chosen by hand.
    const assets::LoadedScene plane = assets::builtinScene("plane");
    const RayScene builtin(plane.scene);
    const ShadingPoints camera = fromCamera(builtin, assets::makeCamera(plane.camera, 24, 16), 24, 16);
    for (bool cosine : {true, false}) {
        RenderSettings settings;
        settings.samplesPerPixel = 64;
        const Reference r = render(builtin, camera, reference::AmbientOcclusion{kInfinity, cosine}, settings);
        int surfaces = 0;
        for (std::size_t i = 0; i < camera.points.size(); ++i) {
            if (!camera.points[i].surface()) continue;
            ++surfaces;
            CHECK(std::abs(r.value.pixels[i] - 1.0) < 1e-3);
        }
        CHECK(surfaces > 100);
        const Reference hand = render(scene, test::pointsAt(pointsNearCentre(), {0, 1, 0}), reference::AmbientOcclusion{}, settings);
        for (float v : hand.value.pixels) CHECK(std::abs(v - 1.0) < 1e-3);
    }
}

TEST_CASE("AO under a coaxial disc is one minus the view factor and 1 with a shorter radius", "[reference][ao]") {
    const double h = 1.0, a = 0.75;
    // 1024 segments: the inscribed polygon's area is short of the disc's by (2 pi/1024)^2/6 ~ 6e-6.
    const RayScene scene(test::meshScene({test::quadMesh(kFloor), test::discMesh({0, h, 0}, a, 1024)}));
    const std::vector<glm::dvec3> at = pointsNearCentre();
    const ShadingPoints points = test::pointsAt(at, {0, 1, 0});
    RenderSettings settings;
    settings.samplesPerPixel = 8192;
    // Cosine-weighted: 1 - F with the view factor from a differential area at distance r
    // from the axis to a parallel disc, F = (1 - (h^2 + r^2 - a^2) / sqrt((h^2 + r^2 + a^2)^2
    // - 4 r^2 a^2)) / 2, which on the axis is a^2 / (h^2 + a^2).
    const Reference cosine = render(scene, points, reference::AmbientOcclusion{kInfinity, true}, settings);
    for (std::size_t i = 0; i < at.size(); ++i) {
        const double r2 = at[i].x * at[i].x + at[i].z * at[i].z;
        const double f = 0.5 * (1 - (h * h + r2 - a * a) / std::sqrt(std::pow(h * h + r2 + a * a, 2) - 4 * r2 * a * a));
        const double expected = 1 - f;
        // A mean of n Bernoulli trials has sigma = sqrt(p (1 - p) / n); stratification only lowers it.
        const double sigma = std::sqrt(expected * (1 - expected) / settings.samplesPerPixel);
        CHECK(std::abs(cosine.value.pixels[i] - expected) < 4 * sigma);
    }
    // On the axis, 32 independent pixels: their mean within 4 standard errors, a tolerance
    // from the estimator's actual spread (tighter than the Bernoulli bound above).
    const std::vector<glm::dvec3> axis(32, glm::dvec3(0.0));
    settings.samplesPerPixel = 1024;
    const Reference onAxis = render(scene, test::pointsAt(axis, {0, 1, 0}), reference::AmbientOcclusion{kInfinity, true}, settings);
    const test::Stats st = test::stats(onAxis.value, 0);
    CHECK(std::abs(st.mean - h * h / (h * h + a * a)) < 4 * st.stddev / std::sqrt(double(st.n)) + 1e-9);
    // Uniform-weighted, on the axis: 1 - (1 - cos alpha) = cos alpha, alpha the disc's half-angle.
    const Reference uniform = render(scene, test::pointsAt(axis, {0, 1, 0}), reference::AmbientOcclusion{kInfinity, false}, settings);
    const test::Stats su = test::stats(uniform.value, 0);
    CHECK(std::abs(su.mean - h / std::sqrt(h * h + a * a)) < 4 * su.stddev / std::sqrt(double(su.n)) + 1e-9);
    // With a radius below the disc's height nothing is within reach.
    settings.samplesPerPixel = 256;
    const Reference limited = render(scene, points, reference::AmbientOcclusion{0.99 * h, true}, settings);
    for (float v : limited.value.pixels) CHECK(v == 1.0f);
}

TEST_CASE("Obscurance under a ceiling matches its one-dimensional integral", "[reference][obscurance]") {
    // An infinite-looking ceiling at height h: a ray at angle theta hits at d = h / cos(theta).
    const double h = 0.5, dmax = 1.5;
    const test::QuadCorners ceiling{{{-500, h, -500}, {500, h, -500}, {500, h, 500}, {-500, h, 500}}};
    const RayScene scene(test::meshScene({test::quadMesh(kFloor), test::quadMesh(ceiling)}));
    const ShadingPoints points = test::pointsAt(pointsNearCentre(), {0, 1, 0});
    RenderSettings settings;
    settings.samplesPerPixel = 8192;
    for (auto falloff : {ObscuranceFalloff::None, ObscuranceFalloff::Linear, ObscuranceFalloff::Quadratic,
                         ObscuranceFalloff::Smooth})
        for (const bool cosine : {true, false}) {
            CAPTURE(static_cast<int>(falloff), cosine);
            // W = (1/pi) Int rho cos dw = Int_0^{pi/2} rho(h / cos t) 2 cos t sin t dt, or uniformly
            // weighted (1/(2 pi)) Int rho dw = Int_0^{pi/2} rho(h / cos t) sin t dt; midpoint rule
            // with 200000 steps: rho jumps (None) or kinks at d = dmax, so the error is at most
            // one step's share there, (pi/2) / 200000 = 8e-6, far inside the sampling's 4 sigma.
            double expected = 0.0;
            const int steps = 200000;
            for (int i = 0; i < steps; ++i) {
                const double t = (i + 0.5) / steps * (kPi / 2);
                const double density = cosine ? 2 * std::cos(t) * std::sin(t) : std::sin(t);
                expected += obscuranceWeight(falloff, h / std::cos(t), dmax) * density * (kPi / 2) / steps;
            }
            const Reference r = render(scene, points, Obscurance{dmax, falloff, cosine}, settings);
            // rho is in [0, 1]: the variance of one sample is at most 1/4.
            const double sigma = std::sqrt(0.25 / settings.samplesPerPixel);
            for (float v : r.value.pixels) CHECK(std::abs(v - expected) < 4 * sigma);
        }
    CHECK(obscuranceWeight(ObscuranceFalloff::Smooth, 0.5, 1.0) == Approx(0.5));
    CHECK(obscuranceWeight(ObscuranceFalloff::Quadratic, 0.5, 2.0) == Approx(0.0625));
    CHECK(obscuranceWeight(ObscuranceFalloff::None, 3.0, 2.0) == 1.0);
}

TEST_CASE("The bent normal next to a wall leans away from it by the closed-form angle", "[reference][bent-normal]") {
    // A floor and a huge wall at x = -0.001: every direction with w.x < 0 hits the wall, so the
    // visible set is the half-hemisphere w.x > 0. Its cosine-weighted mean direction is
    // (Int x y dw, Int y^2 dw, 0) over it = (2/3, pi/3, 0) up to a factor (with y up).
    const test::QuadCorners wall{{{-0.001, 0, -500}, {-0.001, 500, -500}, {-0.001, 500, 500}, {-0.001, 0, 500}}};
    const RayScene scene(test::meshScene({test::quadMesh(kFloor), test::quadMesh(wall)}));
    std::vector<glm::dvec3> at(16, glm::dvec3(0.0));
    RenderSettings settings;
    settings.samplesPerPixel = 4096;
    const Reference r = render(scene, test::pointsAt(at, {0, 1, 0}), BentNormal{}, settings);
    const glm::dvec3 expected = glm::normalize(glm::dvec3(2.0 / 3.0, kPi / 3.0, 0.0));
    for (int c = 0; c < 3; ++c) {
        const test::Stats st = test::stats(r.value, c);
        INFO("component " << c << ": " << st.mean << " vs " << expected[c]);
        CHECK(std::abs(st.mean - expected[c]) < 4 * st.stddev / std::sqrt(double(st.n)) + 1e-9);
    }
}

TEST_CASE("Bent normals of symmetric configurations are the normal", "[reference][bent-normal]") {
    const RayScene scene(test::meshScene({test::quadMesh(kFloor), test::discMesh({0, 1, 0}, 0.75, 256)}));
    const ShadingPoints points = test::pointsAt({{0, 0, 0}}, {0, 1, 0});
    RenderSettings settings;
    settings.samplesPerPixel = 8192;
    const Reference r = render(scene, points, BentNormal{}, settings);
    // The mean of cosine-distributed unoccluded directions has a horizontal part of zero mean;
    // its spread per component is below 1/sqrt(n) of the vertical part's size.
    CHECK(std::abs(r.value.pixels[0]) < 4.0 / std::sqrt(settings.samplesPerPixel / 2.0));
    CHECK(r.value.pixels[1] > 0.99);
    CHECK(std::abs(r.value.pixels[2]) < 4.0 / std::sqrt(settings.samplesPerPixel / 2.0));
}

TEST_CASE("An obscurance falloff outside its enumerators and a negative thread count are refused", "[reference][obscurance]") {
    // Before, an unknown falloff weighed every hit 1 (fully open) and -1 threads meant all cores.
    const RayScene scene(test::meshScene({test::quadMesh(kFloor)}));
    const ShadingPoints points = test::pointsAt(pointsNearCentre(), {0, 1, 0});
    RenderSettings settings;
    settings.samplesPerPixel = 4;
    Obscurance unknown;
    unknown.falloff = static_cast<ObscuranceFalloff>(9);
    CHECK_THROWS_WITH(render(scene, points, unknown, settings), Catch::Contains("Obscurance::falloff"));
    settings.threads = -1;
    CHECK_THROWS_WITH(render(scene, points, reference::AmbientOcclusion{}, settings), Catch::Contains("RenderSettings::threads"));
    settings.threads = 1;
    CHECK_NOTHROW(render(scene, points, reference::AmbientOcclusion{}, settings));
}
