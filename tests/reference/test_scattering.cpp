// Single scattering against double-precision adaptive quadrature of the airlight integral.
#include "reference_helpers.hpp"

#include <catch2/catch.hpp>

#include <functional>

using namespace obscura;
using namespace obscura::reference;

namespace {

// Adaptive Simpson quadrature to an absolute tolerance.
double simpson(const std::function<double(double)>& f, double a, double b, double fa, double fm, double fb, double whole,
               double tol, int depth) {
    const double m = 0.5 * (a + b), lm = 0.5 * (a + m), rm = 0.5 * (m + b);
    const double flm = f(lm), frm = f(rm);
    const double left = (m - a) / 6 * (fa + 4 * flm + fm), right = (b - m) / 6 * (fm + 4 * frm + fb);
    if (depth <= 0 || std::abs(left + right - whole) <= 15 * tol) return left + right + (left + right - whole) / 15;
    return simpson(f, a, m, fa, flm, fm, left, tol / 2, depth - 1) + simpson(f, m, b, fm, frm, fb, right, tol / 2, depth - 1);
}
double integrate(const std::function<double(double)>& f, double a, double b, double tol) {
    const double fa = f(a), fb = f(b), fm = f(0.5 * (a + b));
    return simpson(f, a, b, fa, fm, fb, (b - a) / 6 * (fa + 4 * fm + fb), tol, 50);
}

// Length of the segment from p toward unit w (length `len`) inside the box [lo, hi].
double inside(glm::dvec3 p, glm::dvec3 w, double len, glm::dvec3 lo, glm::dvec3 hi) {
    double t0 = 0, t1 = len;
    for (int a = 0; a < 3; ++a) {
        if (w[a] == 0) {
            if (p[a] < lo[a] || p[a] > hi[a]) return 0;
            continue;
        }
        double ta = (lo[a] - p[a]) / w[a], tb = (hi[a] - p[a]) / w[a];
        if (ta > tb) std::swap(ta, tb);
        t0 = std::max(t0, ta);
        t1 = std::min(t1, tb);
    }
    return std::max(0.0, t1 - t0);
}

} // namespace

TEST_CASE("Single scattering matches adaptive quadrature for every phase function", "[reference][media]") {
    const auto phase = GENERATE(PhaseFunction::Isotropic, PhaseFunction::HenyeyGreenstein, PhaseFunction::Rayleigh);
    // A light inside the box, and one outside it (the light path then leaves the medium).
    const bool lightInside = GENERATE(true, false);
    CAPTURE(static_cast<int>(phase), lightInside);
    Scene s; // no geometry: nothing occludes
    s.materials.push_back({});
    Medium m;
    m.boxMin = {-1, -1, -1};
    m.boxMax = {1, 1, 1};
    m.scattering = {0.5f, 0.8f, 1.1f};
    m.absorption = {0.2f, 0.1f, 0.0f};
    m.phase = phase;
    m.anisotropy = 0.4f;
    s.media.push_back(m);
    Light l;
    l.position = lightInside ? glm::vec3(0.3f, 0.5f, 0.2f) : glm::vec3(0.2f, 2.5f, -0.4f);
    l.intensity = 2.0f;
    l.color = {1.0f, 0.5f, 0.25f};
    s.lights.push_back(l);
    const RayScene scene(s);
    const glm::dvec3 origin(0.1, -0.2, -3.0), dir = glm::normalize(glm::dvec3(0.05, 0.1, 1.0));
    RenderSettings settings;
    settings.samplesPerPixel = 512;
    const Reference r = render(scene, test::repeatedRay(origin, dir, 64), SingleScattering{0, true}, settings);

    // The view ray enters the box at t0 and leaves at t1.
    double t0 = 0, t1 = 1e9;
    for (int a = 0; a < 3; ++a) {
        double ta = (m.boxMin[a] - origin[a]) / dir[a], tb = (m.boxMax[a] - origin[a]) / dir[a];
        if (ta > tb) std::swap(ta, tb);
        t0 = std::max(t0, ta);
        t1 = std::min(t1, tb);
    }
    for (int c = 0; c < 3; ++c) {
        const double ss = m.scattering[c], st = m.scattering[c] + m.absorption[c], I = l.intensity * l.color[c];
        const auto integrand = [&](double t) {
            const glm::dvec3 x = origin + t * dir, toLight = glm::dvec3(l.position) - x;
            const double d = glm::length(toLight);
            const glm::dvec3 w = toLight / d;
            const double p = phaseFunction(m.phase, m.anisotropy, glm::dot(-w, -dir));
            return ss * std::exp(-st * (t - t0)) * p * I / (d * d) *
                   std::exp(-st * inside(x, w, d, glm::dvec3(m.boxMin), glm::dvec3(m.boxMax)));
        };
        const double expected = integrate(integrand, t0, t1, 1e-12);
        const test::Stats st64 = test::stats(r.value, c);
        INFO("channel " << c << ": " << st64.mean << " vs quadrature " << expected << " (stddev " << st64.stddev << ")");
        CHECK(std::abs(st64.mean - expected) < 4 * st64.stddev / std::sqrt(double(st64.n)));
        // The view transmittance is exact.
        const double t = std::exp(-st * (t1 - t0));
        (void)t;
    }
    const double meanT = (std::exp(-0.7 * (t1 - t0)) + std::exp(-0.9 * (t1 - t0)) + std::exp(-1.1 * (t1 - t0))) / 3;
    CHECK(r.value.pixels[3] == Approx(meanT).epsilon(1e-6));
}

TEST_CASE("Dense and vanishing media stay finite and bounded", "[reference][media][stability]") {
    for (float sigma : {0.0f, 1e-8f, 1e4f}) {
        Scene s;
        s.materials.push_back({});
        Medium m;
        m.boxMin = {-1, -1, -1};
        m.boxMax = {1, 1, 1};
        m.scattering = glm::vec3(sigma);
        s.media.push_back(m);
        Light l;
        l.position = {0, 0, 0}; // on the view ray: the equiangular pdf is at its sharpest
        s.lights.push_back(l);
        const RayScene scene(s);
        RenderSettings settings;
        settings.samplesPerPixel = 64;
        const Reference r = render(scene, test::repeatedRay({0, 0, -3}, {0, 0, 1}, 8), SingleScattering{}, settings);
        for (float v : r.value.pixels) {
            CHECK(std::isfinite(v));
            CHECK(v >= 0.0f);
        }
        if (sigma == 0.0f) CHECK(r.value.pixels[0] == 0.0f);
    }
}
