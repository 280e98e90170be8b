// Single scattering against double-precision adaptive quadrature of the airlight integral,
// and the phase functions against hand-computed values.
#include "quadrature.hpp"
#include "reference_helpers.hpp"

#include <catch2/catch.hpp>

#include <functional>

using namespace obscura;
using namespace obscura::reference;
using test::kPi;

namespace {

using test::integrate;

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

// Henyey-Greenstein and Rayleigh written out independently of the library.
double phaseByHand(PhaseFunction f, double g, double c) {
    if (f == PhaseFunction::Isotropic) return 1 / (4 * kPi);
    if (f == PhaseFunction::Rayleigh) return 3 / (16 * kPi) * (1 + c * c);
    if (f == PhaseFunction::Schlick) {
        const double cubic = 1.55 * g - 0.55 * g * g * g, bound = 1 - (1 - std::abs(g)) * (1 - std::abs(g));
        const double k = std::abs(cubic) < bound ? cubic : std::copysign(bound, g);
        return (1 - k * k) / (4 * kPi * (1 - k * c) * (1 - k * c));
    }
    return (1 - g * g) / (4 * kPi * std::pow(1 + g * g - 2 * g * c, 1.5));
}

// The density of the tests' media written out: Height as exp(-k (y - y0)); a Grid whose
// values rise linearly along x (v_i = a + b i, one cell in y and z), trilinear between cell
// centres and constant beyond the outer ones: a + b clamp(u n - 1/2, 0, n - 1), u = the
// box-relative x.
double densityByHand(const Medium& m, const glm::dvec3& x) {
    for (int a = 0; a < 3; ++a)
        if (x[a] < m.boxMin[a] || x[a] > m.boxMax[a]) return 0.0;
    if (m.density == MediumDensity::Height) return std::exp(-double(m.heightFalloff) * (x.y - m.boxMin.y));
    if (m.density == MediumDensity::Grid) {
        const auto& v = m.grid->values;
        const double n = double(v.size()), a = v[0], b = v[1] - v[0];
        const double u = (x.x - m.boxMin.x) / (double(m.boxMax.x) - m.boxMin.x);
        return a + b * std::clamp(u * n - 0.5, 0.0, n - 1.0);
    }
    return 1.0;
}

// Integral of the density along p + s w, s in [0, len]: midpoint rule, 4000 points (the
// densities are smooth or piecewise linear: far below the Monte Carlo error checked).
double densityPath(const Medium& m, const glm::dvec3& p, const glm::dvec3& w, double len) {
    if (m.density == MediumDensity::Constant) return inside(p, w, len, glm::dvec3(m.boxMin), glm::dvec3(m.boxMax));
    const double end = std::min(len, 10.0); // the boxes here are 2 wide
    double sum = 0.0;
    for (int i = 0; i < 4000; ++i) sum += densityByHand(m, p + (end * (i + 0.5) / 4000) * w);
    return sum * end / 4000;
}

struct MediumCase {
    Scene scene;
    glm::dvec3 origin{0.1, -0.2, -3.0}, dir = glm::normalize(glm::dvec3(0.05, 0.1, 1.0));
    // Visibility of the light from a point, as the test's own geometry dictates.
    std::function<bool(const glm::dvec3&)> visible = [](const glm::dvec3&) { return true; };

    // The airlight integral of channel c, by quadrature, along the view ray inside the box.
    double quadrature(int c) const {
        const Medium& m = scene.media[0];
        const Light& l = scene.lights[0];
        double t0 = 0, t1 = 1e9;
        for (int a = 0; a < 3; ++a) {
            double ta = (m.boxMin[a] - origin[a]) / dir[a], tb = (m.boxMax[a] - origin[a]) / dir[a];
            if (ta > tb) std::swap(ta, tb);
            t0 = std::max(t0, ta);
            t1 = std::min(t1, tb);
        }
        const double ss = m.scattering[c], st = m.scattering[c] + m.absorption[c];
        const double radiance = l.intensity * l.color[c];
        const auto f = [&](double t) {
            const glm::dvec3 x = origin + t * dir;
            glm::dvec3 w;
            double d = 1e300, falloff = 1.0;
            if (l.type == LightType::Directional) {
                w = -glm::normalize(glm::dvec3(l.direction));
            } else {
                const glm::dvec3 toLight = glm::dvec3(l.position) - x;
                d = glm::length(toLight);
                w = toLight / d;
                falloff = 1 / (d * d);
                if (l.type == LightType::Spot) {
                    const double cosAngle = glm::dot(-w, glm::normalize(glm::dvec3(l.direction)));
                    const double ci = std::cos(double(l.innerAngle)), co = std::cos(double(l.outerAngle));
                    const double s = std::clamp((cosAngle - co) / (ci - co), 0.0, 1.0);
                    falloff *= s * s * (3 - 2 * s);
                }
            }
            if (!visible(x)) return 0.0;
            // Scattering angle between the light's travel direction (-w) and the way to the camera (-dir).
            const double p = phaseByHand(m.phase, m.anisotropy, glm::dot(-w, -dir));
            return ss * densityByHand(m, x) * std::exp(-st * densityPath(m, origin + t0 * dir, dir, t - t0)) * p * radiance *
                   falloff * std::exp(-st * densityPath(m, x, w, d));
        };
        // Far below the Monte Carlo error it checks (heterogeneous media: their density
        // integrals' 4000 points bound it at about 1e-7).
        return integrate(f, t0, t1, m.density == MediumDensity::Constant ? 1e-8 : 1e-6, m.density == MediumDensity::Constant ? 256 : 32);
    }
};

MediumCase makeCase(const Light& light, const Medium& medium) {
    MediumCase c;
    c.scene.materials.push_back({});
    c.scene.media.push_back(medium);
    c.scene.lights.push_back(light);
    return c;
}

Medium unitBox(glm::vec3 scattering, glm::vec3 absorption, PhaseFunction phase, float g) {
    Medium m;
    m.boxMin = {-1, -1, -1};
    m.boxMax = {1, 1, 1};
    m.scattering = scattering;
    m.absorption = absorption;
    m.phase = phase;
    m.anisotropy = g;
    return m;
}

// The estimate of each channel over `copies` independent pixels, within 4 standard errors of
// the quadrature (and both finite).
void checkAgainstQuadrature(const MediumCase& c, int spp, bool shadows = true, int copies = 64) {
    const RayScene scene(c.scene);
    RenderSettings settings;
    settings.samplesPerPixel = spp;
    const Reference r = render(scene, test::repeatedRay(c.origin, c.dir, copies), SingleScattering{0, shadows}, settings);
    for (int ch = 0; ch < 3; ++ch) {
        const double expected = c.quadrature(ch);
        const test::Stats st = test::stats(r.value, ch);
        INFO("channel " << ch << ": " << st.mean << " vs quadrature " << expected << " (stddev " << st.stddev << ")");
        CHECK(std::isfinite(st.mean));
        CHECK(std::abs(st.mean - expected) <= 4 * st.stddev / std::sqrt(double(st.n)) + 1e-12 * std::abs(expected));
    }
}

} // namespace

TEST_CASE("Phase functions match hand-computed values and integrate to 1", "[reference][media]") {
    CHECK(phaseFunction(PhaseFunction::Isotropic, 0, 0.3) == Approx(0.0795774715));
    CHECK(phaseFunction(PhaseFunction::Rayleigh, 0, 1.0) == Approx(6.0 / (16 * kPi)));
    // HG with g = 0.5 straight ahead: (1 - 0.25) / (4 pi (0.25)^1.5) = 0.75 / (4 pi 0.125) = 1.5 / pi.
    CHECK(phaseFunction(PhaseFunction::HenyeyGreenstein, 0.5, 1.0) == Approx(1.5 / kPi));
    // Schlick, g = 0.5: k = 0.775 - 0.06875 = 0.70625; straight ahead (1 + k) / (4 pi (1 - k)).
    CHECK(phaseFunction(PhaseFunction::Schlick, 0.5, 1.0) == Approx(1.70625 / (4 * kPi * 0.29375)));
    for (auto f : {PhaseFunction::Isotropic, PhaseFunction::HenyeyGreenstein, PhaseFunction::Rayleigh, PhaseFunction::Schlick}) {
        // Integral over the sphere = 2 pi Int_{-1}^{1} p(c) dc (midpoint rule, 1e5 steps).
        double sum = 0;
        const int steps = 100000;
        for (int i = 0; i < steps; ++i) sum += phaseFunction(f, 0.7, -1 + 2 * (i + 0.5) / steps) * 2.0 / steps;
        CHECK(2 * kPi * sum == Approx(1.0).epsilon(1e-4));
    }
    // Schlick's cubic passes 1 near g = 0.97: k stays below 1, the phase positive and finite.
    for (double g : {0.9, 0.97, 0.999, -0.97}) {
        CAPTURE(g);
        CHECK(std::abs(schlickK(g)) < 1.0);
        CHECK(phaseFunction(PhaseFunction::Schlick, g, -1.0) > 0.0);
        CHECK(std::isfinite(phaseFunction(PhaseFunction::Schlick, g, 1.0)));
    }
}

TEST_CASE("Single scattering matches adaptive quadrature for every phase function", "[reference][media]") {
    const auto phase = GENERATE(PhaseFunction::Isotropic, PhaseFunction::HenyeyGreenstein, PhaseFunction::Rayleigh,
                                PhaseFunction::Schlick);
    // A light inside the box, and one outside it (the light path then leaves the medium).
    const bool lightInside = GENERATE(true, false);
    CAPTURE(static_cast<int>(phase), lightInside);
    Light l;
    l.position = lightInside ? glm::vec3(0.3f, 0.5f, 0.2f) : glm::vec3(0.2f, 2.5f, -0.4f);
    l.intensity = 2.0f;
    l.color = {1.0f, 0.5f, 0.25f};
    MediumCase c = makeCase(l, unitBox({0.5f, 0.8f, 1.1f}, {0.2f, 0.1f, 0.0f}, phase, 0.4f));
    checkAgainstQuadrature(c, 512);
    // The view transmittance (4th channel) is exact: exp(-sigma_t L) averaged over RGB.
    const RayScene scene(c.scene);
    const Reference r = render(scene, test::repeatedRay(c.origin, c.dir, 1), SingleScattering{}, RenderSettings{});
    double t0 = 0, t1 = 1e9;
    for (int a = 0; a < 3; ++a) {
        double ta = (-1 - c.origin[a]) / c.dir[a], tb = (1 - c.origin[a]) / c.dir[a];
        if (ta > tb) std::swap(ta, tb);
        t0 = std::max(t0, ta);
        t1 = std::min(t1, tb);
    }
    const double meanT = (std::exp(-0.7 * (t1 - t0)) + std::exp(-0.9 * (t1 - t0)) + std::exp(-1.1 * (t1 - t0))) / 3;
    CHECK(r.value.pixels[3] == Approx(meanT).epsilon(1e-6));
}

TEST_CASE("Spot and directional lights in media match quadrature", "[reference][media]") {
    Light spot;
    spot.type = LightType::Spot;
    spot.position = {0.0f, 0.8f, 0.0f};
    spot.direction = {0.0f, -1.0f, 0.1f};
    spot.innerAngle = 0.3f;
    spot.outerAngle = 0.6f;
    spot.intensity = 3.0f;
    checkAgainstQuadrature(makeCase(spot, unitBox(glm::vec3(0.6f), glm::vec3(0.1f), PhaseFunction::HenyeyGreenstein, -0.3f)),
                           1024);
    Light sun;
    sun.type = LightType::Directional;
    sun.direction = glm::normalize(glm::vec3(0.3f, -1.0f, 0.2f));
    sun.intensity = 1.5f;
    checkAgainstQuadrature(makeCase(sun, unitBox(glm::vec3(0.4f), glm::vec3(0.0f), PhaseFunction::Rayleigh, 0.0f)), 512);
}

TEST_CASE("Coloured dense media keep every channel unbiased", "[reference][media][stability]") {
    // One channel dense, two thin: a sampler matched to the mean extinction starves the thin
    // channels (the tail they need is too light).
    for (float dense : {300.0f, 2000.0f}) {
        CAPTURE(dense);
        Light sun;
        sun.type = LightType::Directional;
        sun.direction = glm::normalize(glm::vec3(0.2f, -1.0f, 0.1f));
        checkAgainstQuadrature(makeCase(sun, unitBox({dense, 0.5f, 0.5f}, glm::vec3(0.0f), PhaseFunction::Isotropic, 0.0f)),
                               1024);
    }
}

TEST_CASE("Shadowed media match quadrature with the occluder's visibility", "[reference][media]") {
    // A large horizontal plate at y = 0.5 over x < 0.2 shadows the directional light for
    // points below it on that side.
    Light sun;
    sun.type = LightType::Directional;
    sun.direction = {0.0f, -1.0f, 0.0f};
    MediumCase c = makeCase(sun, unitBox(glm::vec3(0.5f), glm::vec3(0.1f), PhaseFunction::HenyeyGreenstein, 0.2f));
    c.scene.meshes.push_back({test::quadMesh({{{-50, 0.5, -50}, {0.2, 0.5, -50}, {0.2, 0.5, 50}, {-50, 0.5, 50}}}),
                              glm::mat4(1.0f), 0, "plate"});
    c.dir = glm::normalize(glm::dvec3(0.3, 0.02, 1.0));
    c.visible = [](const glm::dvec3& x) { return !(x.x < 0.2 && x.y < 0.5); };
    checkAgainstQuadrature(c, 1024);
}

TEST_CASE("Vanishing and very dense media match the limits", "[reference][media][stability]") {
    Light l;
    l.position = {0.0f, 0.3f, 0.0f};
    for (float sigma : {0.0f, 1e-8f, 1e4f}) {
        CAPTURE(sigma);
        MediumCase c = makeCase(l, unitBox(glm::vec3(sigma), glm::vec3(0.0f), PhaseFunction::Isotropic, 0.0f));
        c.dir = glm::dvec3(0, 0, 1);
        c.origin = glm::dvec3(0, 0, -3);
        if (sigma == 0.0f) {
            const RayScene scene(c.scene);
            const Reference r = render(scene, test::repeatedRay(c.origin, c.dir, 4), SingleScattering{}, RenderSettings{});
            for (int i = 0; i < 4; ++i) CHECK(r.value.pixels[static_cast<std::size_t>(i) * 4] == 0.0f);
            CHECK(r.value.pixels[3] == 1.0f);
        } else {
            checkAgainstQuadrature(c, 256);
        }
    }
}

TEST_CASE("Forward scattering is brighter looking toward the light", "[reference][media]") {
    // The convention: p(cos) with cos between the light's travel direction and the way to the
    // camera; g > 0 sends light onward, so a camera facing the sun sees more.
    Light sun;
    sun.type = LightType::Directional;
    sun.direction = {0.0f, 0.0f, 1.0f}; // travels along +z
    MediumCase c = makeCase(sun, unitBox(glm::vec3(0.3f), glm::vec3(0.0f), PhaseFunction::HenyeyGreenstein, 0.8f));
    const RayScene scene(c.scene);
    RenderSettings settings;
    settings.samplesPerPixel = 256;
    const Reference facing = render(scene, test::repeatedRay({0, 0, 3}, {0, 0, -1}, 64), SingleScattering{}, settings);
    const Reference away = render(scene, test::repeatedRay({0, 0, -3}, {0, 0, 1}, 64), SingleScattering{}, settings);
    // Facing the light (cos = 1): every point of the 2-unit path sees transmittance
    // e^{-sigma (1 - z)} e^{-sigma (z + 1)} = e^{-2 sigma}: Ls = sigma E p(1) 2 e^{-2 sigma}.
    // Away (cos = -1): e^{-2 sigma u} over u in [0, 2]: Ls = sigma E p(-1) (1 - e^{-4 sigma}) / (2 sigma).
    const double sigma = 0.3, e = 1.0;
    const double expectedFacing = sigma * e * phaseByHand(PhaseFunction::HenyeyGreenstein, 0.8, 1.0) * 2 * std::exp(-2 * sigma);
    const double expectedAway =
        sigma * e * phaseByHand(PhaseFunction::HenyeyGreenstein, 0.8, -1.0) * (1 - std::exp(-4 * sigma)) / (2 * sigma);
    const test::Stats f = test::stats(facing.value, 0), a = test::stats(away.value, 0);
    CHECK(std::abs(f.mean - expectedFacing) <= 4 * f.stddev / std::sqrt(double(f.n)) + 1e-12);
    CHECK(std::abs(a.mean - expectedAway) <= 4 * a.stddev / std::sqrt(double(a.n)) + 1e-12);
    CHECK(f.mean > 100 * a.mean); // p(1) / p(-1) = ((1 + g) / (1 - g))^3 = 729
}

TEST_CASE("Height fog and density grids match quadrature (closed-form densities)", "[reference][media]") {
    Light l;
    l.type = LightType::Point;
    l.position = {0.3f, 0.4f, 0.2f};
    l.intensity = 4.0f;
    Medium m = unitBox(glm::vec3(0.6f, 0.9f, 1.2f), glm::vec3(0.1f), PhaseFunction::HenyeyGreenstein, 0.3f);
    SECTION("exponential height fog: exact transmittance") {
        m.density = MediumDensity::Height;
        m.heightFalloff = 1.5f;
        checkAgainstQuadrature(makeCase(l, m), 256);
    }
    SECTION("a density grid: ratio tracking") {
        m.density = MediumDensity::Grid;
        m.grid = std::make_shared<DensityGrid>(DensityGrid{{4, 1, 1}, {0.5f, 1.0f, 1.5f, 2.0f}});
        checkAgainstQuadrature(makeCase(l, m), 256);
    }
}

TEST_CASE("Height fog taller than exp's range keeps a finite transmittance", "[reference][media][stability]") {
    // A ray down through 2000 units of fog with falloff 1: the density climbs by e^2000 along
    // it; the transmittance is exp(-sigma_t (1 - e^-1990) / 1) below the top 10 units.
    Medium m = unitBox(glm::vec3(0.01f), glm::vec3(0.0f), PhaseFunction::Isotropic, 0.0f);
    m.boxMin = {-1.0f, 0.0f, -1.0f};
    m.boxMax = {1.0f, 2000.0f, 1.0f};
    m.density = MediumDensity::Height;
    m.heightFalloff = 1.0f;
    Light l;
    l.type = LightType::Directional;
    l.direction = {0.0f, -1.0f, 0.0f};
    MediumCase c = makeCase(l, m);
    const RayScene scene(c.scene);
    RenderSettings settings;
    settings.samplesPerPixel = 8;
    const Reference r = render(scene, test::repeatedRay({0.0, 2100.0, 0.0}, {0.0, -1.0, 0.0}, 4), SingleScattering{0, false}, settings);
    for (float v : r.value.pixels) CHECK(std::isfinite(v));
    // Straight down the whole box: the density integral is (1 - e^-2000) / 1 = 1.
    CHECK(r.value.at(0, 0, 3) == Approx(std::exp(-0.01)).epsilon(1e-6)); // the image stores float
}
