// Horizon-based AO (AoMethod::Horizon, GTAO-style) against its own slice integral, on a
// floor beside a box seen from straight above.
//
// Why this view: in an orthographic view from above every slice plane is vertical and the
// view direction is the floor's normal, so the slice weights are all 1 and the normal's angle
// in each slice is 0. The depth buffer holds the box's top (its sides are edge-on), so in a
// direction phi the highest point within the radius r is the nearest point of the top's edge,
// at horizontal distance t(phi), if it lies within r: its elevation e has
// sin^2 e = h^2 / (t^2 + h^2), h the box's height. GTAO's arc for a horizon at elevation e,
// cosine-weighted with the normal at angle 0, is (1 - sin^2 e) / 2 per side, against 1/2
// open, so
//   AO = 1 - (1 / 2pi) Integral_0^2pi sin^2 e(phi) dphi.
// This is what the method estimates, not AO_r: a direction whose ray would meet the box's
// side within r while its top edge is beyond r counts as open here. (AO_r itself is tested on
// the other methods in test_ambient_occlusion.cpp.) Not covered: the projected normal's
// weight and angle g of oblique slices, which this view makes 1 and 0.
#include "ao_fixture.hpp"

#include <catch2/catch.hpp>
#include <glm/gtc/constants.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

using namespace obscura;

namespace {

constexpr double kPi = glm::pi<double>();

// The box [-b, b] x [0, h] x [-b, b] on the floor, the view and the settings.
struct BoxView {
    double b = 0.5, h = 0.5;
    double halfHeight = 1.6; // orthographic: 3.2 world units over the image's height
    int size = 128;          // pixels; 40 a world unit, so the box's edges lie on pixel edges
    double radius = 1.0;
    int slices = 256, steps = 64;

    double pixel() const { return 2.0 * halfHeight / size; }
    double spacing() const { return radius / steps; } // between depth samples, world units
    double lambda() const { return 0.72 * pixel(); }  // sqrt(1/2) pixels and float rounding
};

// Where the horizontal ray from (x, z) in `direction` enters and leaves the box's
// footprint (slab method); none when it misses.
struct Crossing {
    bool hit = false;
    double in = 0.0, out = 0.0;
};

Crossing crossFootprint(double x, double z, glm::dvec2 direction, double b) {
    const double o[2] = {x, z}, d[2] = {direction.x, direction.y};
    double lo = 0.0, hi = 1e30;
    for (int axis = 0; axis < 2; ++axis) {
        if (std::abs(d[axis]) < 1e-15) {
            if (std::abs(o[axis]) > b) return {};
            continue;
        }
        double t0 = (-b - o[axis]) / d[axis], t1 = (b - o[axis]) / d[axis];
        if (t0 > t1) std::swap(t0, t1);
        lo = std::max(lo, t0);
        hi = std::min(hi, t1);
    }
    return hi > lo ? Crossing{true, lo, hi} : Crossing{};
}

// sin^2 of the horizon's elevation for the box's top edge at horizontal distance t (0 when
// that point is beyond the radius).
double sin2Elevation(double t, const BoxView& v) {
    const double d2 = t * t + v.h * v.h;
    return d2 <= v.radius * v.radius ? v.h * v.h / d2 : 0.0;
}

// The least and the most sin^2 e the shader can find in `direction`. Its j-th depth sample
// is the pixel holding the point at (j + jitter) * spacing along the direction (the offset
// rounded per axis from the pixel's centre); the box's edges lie on pixel edges, so a sample
// is on the top exactly when that point is inside the footprint. The nearest such sample lies
// within a spacing past the entry, when the chord is at least a spacing long, and every one
// lies at least the entry away; a pixel's centre is at most half a pixel's diagonal (lambda)
// from the point it holds.
std::pair<double, double> sin2Window(double x, double z, glm::dvec2 direction, const BoxView& v) {
    const Crossing c = crossFootprint(x, z, direction, v.b);
    if (!c.hit) return {0.0, 0.0};
    const double lambda = v.lambda();
    const double most = sin2Elevation(std::max(c.in - lambda, 0.0), v);
    const double least = c.out - c.in >= v.spacing() ? sin2Elevation(c.in + v.spacing() + lambda, v) : 0.0;
    return {least, most};
}

// The mean over phi in [0, pi) of a slice's occlusion F(phi) = (s(phi) + s(phi + pi)) / 2,
// on `nodes` midpoints, and its total variation over the circle, for s the least and the most
// sin^2 e. The variation measured between nodes can only fall short of the true one (by what
// F does between two nodes, a small share of it: F is monotone between the few angles where
// the box's corners or the radius cut in); 5 % is added for that.
struct SliceIntegral {
    double mean = 0.0, variation = 0.0;
};

struct SliceWindow {
    SliceIntegral least, most;
};

// The nodes' directions phi_i and phi_i + pi, the same for every pixel.
std::vector<glm::dvec2> nodeDirections(int nodes) {
    std::vector<glm::dvec2> d;
    for (int i = 0; i < nodes; ++i) {
        const double phi = kPi * (i + 0.5) / nodes;
        d.push_back({std::cos(phi), std::sin(phi)});
    }
    return d;
}

SliceWindow integrateSlices(double x, double z, const std::vector<glm::dvec2>& directions, const BoxView& v) {
    SliceWindow r;
    const int nodes = static_cast<int>(directions.size());
    std::pair<double, double> first{}, previous{};
    for (int i = 0; i < nodes; ++i) {
        const auto [leastAhead, mostAhead] = sin2Window(x, z, directions[i], v);
        const auto [leastBehind, mostBehind] = sin2Window(x, z, -directions[i], v);
        const std::pair<double, double> f{0.5 * (leastAhead + leastBehind), 0.5 * (mostAhead + mostBehind)};
        r.least.mean += f.first / nodes;
        r.most.mean += f.second / nodes;
        if (i == 0) first = f;
        else {
            r.least.variation += std::abs(f.first - previous.first);
            r.most.variation += std::abs(f.second - previous.second);
        }
        previous = f;
    }
    r.least.variation = 1.05 * (r.least.variation + std::abs(first.first - previous.first));
    r.most.variation = 1.05 * (r.most.variation + std::abs(first.second - previous.second));
    return r;
}

// The horizontal distance from (x, z) to the box's footprint.
double footprintDistance(double x, double z, const BoxView& v) {
    return std::hypot(std::max(std::abs(x) - v.b, 0.0), std::max(std::abs(z) - v.b, 0.0));
}

// The range of the shader's AO at floor point (x, z). Its slices are phi_k = pi (k + u) / slices
// for one offset u per pixel: in each of those strata its value lies between the window's
// F there, so its mean is within variation / slices of F's mean. The CPU's own midpoint rule
// on `nodes` errs by at most variation / nodes.
struct AoWindow {
    double lo = 1.0, hi = 1.0;
};

AoWindow aoWindow(double x, double z, const std::vector<glm::dvec2>& directions, const BoxView& v) {
    // No point of the top within the radius, however the pixels round: exactly open.
    const double reachable = std::max(footprintDistance(x, z, v) - v.lambda(), 0.0);
    if (reachable * reachable + v.h * v.h > v.radius * v.radius) return {};
    const SliceWindow w = integrateSlices(x, z, directions, v);
    const double strata = 1.0 / v.slices + 1.0 / double(directions.size());
    return {1.0 - w.most.mean - w.most.variation * strata, 1.0 - w.least.mean + w.least.variation * strata};
}

} // namespace

TEST_CASE("Horizon AO beside a box seen from above matches its slice integral within the sampling bounds", "[ao]") {
    test::AoFixture f;
    const BoxView v;
    Scene scene = test::floorScene(20.0);
    const glm::mat4 box = glm::scale(glm::translate(glm::mat4(1.0f), glm::vec3(float(-v.b), 0.0f, float(-v.b))),
                                     glm::vec3(float(2.0 * v.b), float(v.h), float(2.0 * v.b)));
    scene.meshes.push_back({test::cubeMesh(), box, 0, "box"});
    const LookAt look{{0.0f, 10.0f, 0.0f}, {0.0f, 0.0f, 0.0f}, {0.0f, 0.0f, -1.0f}};
    f.render(scene, Camera::orthographic(look, float(v.halfHeight), 1.0f, 1.0f, 20.0f), v.size, v.size);
    AmbientOcclusionSettings s;
    s.method = AoMethod::Horizon;
    s.radius = float(v.radius);
    s.rays = 2 * v.slices; // two directions a slice
    s.steps = v.steps;
    const Image ao = f.run(scene, s);
    const std::vector<glm::dvec2> directions = nodeDirections(4096);
    int checked = 0, occluded = 0;
    double occludedWindow = 0.0, meanError = 0.0;
    for (int y = 0; y < v.size; ++y)
        for (int x = 0; x < v.size; ++x) {
            const glm::dvec3 p = f.world(x, y);
            if (!f.geometry(x, y) || std::abs(p.y) > 1e-3) continue; // the floor only
            // Within two pixels of the box the first samples (at least one pixel out) may
            // already be on it.
            if (footprintDistance(p.x, p.z, v) < 2.0 * v.pixel()) continue;
            const auto [lo, hi] = aoWindow(p.x, p.z, directions, v);
            const double value = ao.at(x, y, 0), rounding = std::ldexp(1.0, -12); // half float, to nearest
            CAPTURE(x, y, p.x, p.z, value, lo, hi);
            CHECK(value >= lo - rounding);
            CHECK(value <= hi + rounding);
            meanError += value - 0.5 * (lo + hi);
            ++checked;
            if (hi < 1.0) {
                occludedWindow += 0.5 * (hi - lo);
                ++occluded;
            }
        }
    INFO("mean error " << meanError / checked << " from the window's centre over " << checked << " floor pixels; "
                       << occluded << " of them occluded, their window +-" << occludedWindow / occluded);
    CHECK(checked > 5000);
    CHECK(occluded > 1000);
    // The window must stay a small part of the occlusion it checks (1 - AO reaches about
    // 0.3 beside the box), or a wrong elevation or arc could pass unnoticed.
    CHECK(occludedWindow / occluded < 0.015);
}
