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
// the other methods in test_ambient_occlusion.cpp.) This view makes the projected normal's
// weight and angle g of every slice 1 and 0: the second test, a floor before a wall seen
// obliquely, covers them.
#include "ao_fixture.hpp"

#include <catch2/catch.hpp>
#include <glm/gtc/constants.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>
#include <tuple>
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

// Checks pixels' AO against their windows, plus the half float's rounding (to nearest), and
// keeps what the tests report: the mean error from the windows' centres and the windows' mean
// half-width over the occluded pixels (which must stay small, or a wrong horizon or arc could
// pass unnoticed).
struct WindowTally {
    int checked = 0, occluded = 0;
    double meanError = 0.0, occludedWindow = 0.0;

    void check(double value, AoWindow w) {
        const double rounding = std::ldexp(1.0, -12);
        CHECK(value >= w.lo - rounding);
        CHECK(value <= w.hi + rounding);
        meanError += value - 0.5 * (w.lo + w.hi);
        ++checked;
        if (w.hi < 1.0) {
            occludedWindow += 0.5 * (w.hi - w.lo);
            ++occluded;
        }
    }
    double halfWidth() const { return occludedWindow / occluded; }
    std::string summary() const {
        std::ostringstream out;
        out << "mean error " << meanError / checked << " from the window's centre over " << checked
            << " floor pixels; " << occluded << " of them occluded, their window +-" << halfWidth();
        return out.str();
    }
};

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
    WindowTally tally;
    for (int y = 0; y < v.size; ++y)
        for (int x = 0; x < v.size; ++x) {
            const glm::dvec3 p = f.world(x, y);
            if (!f.geometry(x, y) || std::abs(p.y) > 1e-3) continue; // the floor only
            // Within two pixels of the box the first samples (at least one pixel out) may
            // already be on it.
            if (footprintDistance(p.x, p.z, v) < 2.0 * v.pixel()) continue;
            const AoWindow w = aoWindow(p.x, p.z, directions, v);
            CAPTURE(x, y, p.x, p.z, ao.at(x, y, 0), w.lo, w.hi);
            tally.check(ao.at(x, y, 0), w);
        }
    INFO(tally.summary());
    CHECK(tally.checked > 5000);
    CHECK(tally.occluded > 1000);
    CHECK(tally.halfWidth() < 0.015); // 1 - AO reaches about 0.3 beside the box
}

// A floor before a wall, seen obliquely from the front: the view direction v leans 40 degrees
// below the horizontal, so the floor's normal leans out of most slice planes (weight < 1,
// g != 0, both varying with the slice's angle).
//
// The shader's estimate, per slice: on each side, the largest cos(angle to v) among its depth
// samples that are above the floor's plane and within r, gives the horizon; the arcs of the
// slice follow from it, the weight and g. For a floor point, the samples above its plane are
// on the wall's face (the floor's are on the plane itself), and the wall's face is a plane:
// in the slice's screen coordinates (a along the slice's direction, c across it) its view-
// space height over the point is affine, h = h0 + h_a a + h_c c, and on the line c = 0 the
// cosine h / |o - p| is monotone for a > 0 (it is the sine of the elevation atan2(h, a),
// whose derivative is -h0 / (a^2 + h^2)). A sample is taken at a_j = (j + jitter) r / steps
// along the slice (at least a pixel out) and rounded to a pixel, which moves it by at most
// lambda (half a pixel's diagonal, under a pixel) in a and in c. So (horizonWindow):
// - the most any sample can give is bounded on a line raised by what c can add to h, over
//   the a the samples can reach, feasibility relaxed by what c can change;
// - the least: where the line is on the wall and within r with margin for any rounding, an
//   interval at least a sample spacing long within [pixel, r] holds a sample (the samples
//   there are unclamped, j < steps), near its end where the cosine is larger; its cosine is
//   at least the least over the rectangle it can be rounded into. Shorter, no sample need
//   land there.
// The slice's occlusion is monotone in each side's horizon, so these give its window; the
// estimate (sum of occlusion over sum of open arcs over the slices) follows as in the box
// test, both sums within the variation over the strata.
namespace {

struct WallView {
    double elevation = glm::radians(40.0); // of the view direction below the horizontal
    double halfHeight = 0.6;               // orthographic
    int size = 256;
    double radius = 0.4;
    int slices = 128, steps = 128;

    double pixel() const { return 2.0 * halfHeight / size; }
    double spacing() const { return radius / steps; }
    double lambda() const { return 0.72 * pixel(); } // sqrt(1/2) pixels and float rounding
    double reachPixels() const { return radius / pixel(); }
};

// The wall's face seen from one floor point along one side of one slice (view space; the
// orthographic view direction is +z): its height over p and its world height, affine in the
// screen offsets (a, c).
struct WallLine {
    double h0 = 0.0, ha = 0.0, hc = 0.0; // view-space height (toward the camera) over p
    double y0 = 0.0, ya = 0.0, yc = 0.0; // world y (the face is in view above the floor)

    double h(double a) const { return h0 + ha * a; }
    double length(double a) const { return std::sqrt(a * a + h(a) * h(a)); }
    double cosine(double a) const { return h(a) / length(a); }
    // How far the point moves for a move of 1 across the slice.
    double acrossStretch() const { return std::sqrt(1.0 + hc * hc); }
    // For any unit move in the screen plane.
    double stretch() const { return std::sqrt(1.0 + ha * ha + hc * hc); }
};

struct WallPlane {
    glm::dmat4 view, inverse;
    glm::dvec3 normal, point; // view space

    // World height of the wall's face at view-space screen position q.
    glm::dvec2 heights(glm::dvec3 p, glm::dvec2 q) const {
        const double z = point.z - (normal.x * (q.x - point.x) + normal.y * (q.y - point.y)) / normal.z;
        return {z - p.z, (inverse * glm::dvec4(q, z, 1.0)).y};
    }

    WallLine line(glm::dvec3 p, glm::dvec2 u, glm::dvec2 across) const {
        const glm::dvec2 o = heights(p, glm::dvec2(p)), da = heights(p, glm::dvec2(p) + u) - o,
                         dc = heights(p, glm::dvec2(p) + across) - o;
        return {o.x, da.x, dc.x, o.y, da.y, dc.y};
    }
};

// The a in [lo, hi] on the line c = 0 where y >= yMin and |o - p| <= maxLength; empty: lo > hi.
std::pair<double, double> feasible(const WallLine& w, double lo, double hi, double yMin, double maxLength) {
    if (std::abs(w.ya) > 1e-15) {
        const double at = (yMin - w.y0) / w.ya;
        if (w.ya > 0.0) lo = std::max(lo, at);
        else hi = std::min(hi, at);
    } else if (w.y0 < yMin) return {1.0, 0.0};
    // (1 + ha^2) a^2 + 2 h0 ha a + h0^2 - L^2 <= 0
    const double qa = 1.0 + w.ha * w.ha, qb = 2.0 * w.h0 * w.ha, qc = w.h0 * w.h0 - maxLength * maxLength;
    const double disc = qb * qb - 4.0 * qa * qc;
    if (disc < 0.0) return {1.0, 0.0};
    const double root = std::sqrt(disc);
    return {std::max(lo, (-qb - root) / (2.0 * qa)), std::min(hi, (-qb + root) / (2.0 * qa))};
}

// The least |o - p| on the line over [lo, hi] (convex in a).
double leastLength(const WallLine& w, double lo, double hi) {
    const double vertex = std::clamp(-w.h0 * w.ha / (1.0 + w.ha * w.ha), lo, hi);
    return std::min({w.length(lo), w.length(hi), w.length(vertex)});
}

// The most and the least horizon cosine the shader can find on one side; -1: none.
std::pair<double, double> horizonWindow(const WallLine& w, const WallView& v) {
    const double lambda = v.lambda(), r = v.radius;
    const double crossMove = lambda * w.acrossStretch();
    // Most: a sample at (a, c) has h <= H(a) = h(a, 0) + |h_c| lambda and |o - p| >= the
    // length of (a, h), so where h >= 0 its cosine is at most that of (a, H(a)), a line,
    // monotone in a: largest at an end of the a the samples can reach. Samples with h < 0
    // have a negative cosine, below that bound when it is >= 0; else the length across
    // (c^2 <= lambda^2) can raise theirs by at most lambda^2 / (2 (a^2 + h^2)), and a^2 + h^2
    // is at least the line's least length less |h_c| lambda, squared.
    double most = -1.0;
    {
        const auto [lo, hi] = feasible(w, v.pixel() - lambda, r + lambda, -std::abs(w.yc) * lambda, r * (1.0 + 1e-5) + crossMove);
        if (lo <= hi) {
            WallLine raised = w;
            raised.h0 += std::abs(w.hc) * lambda;
            const double nearest = leastLength(w, lo, hi) - std::abs(w.hc) * lambda;
            const double across = nearest > 0.0 ? 0.5 * lambda * lambda / (nearest * nearest) : 2.0;
            const double line = std::max(raised.cosine(lo), raised.cosine(hi));
            most = std::min(line >= 0.0 ? line : line + across, 1.0);
        }
    }
    // Least: a sample that lands where any rounding keeps it on the wall and within r; it lies
    // in the rectangle a in [a0, a1], |c| <= lambda. Where h >= 0 at its corners the cosine is
    // quasi-concave there ({cos >= k}, k >= 0, is {h >= k |o - p|}: h affine, |o - p| convex),
    // so its least is at a corner; else the cosine on c = 0 (monotone) less its change across c:
    // the point moves by at most crossMove, and unit vectors to x and y differ by at most
    // |x - y| / sqrt(|x| |y|), so the cosine by at most crossMove / (nearest - crossMove).
    double least = -1.0;
    {
        const double boxMove = std::sqrt(2.0) * lambda * w.stretch();
        const double yMargin = 1e-3 + lambda * (std::abs(w.ya) + std::abs(w.yc));
        auto [lo, hi] = feasible(w, v.pixel(), r, yMargin, r * (1.0 - 1e-5) - boxMove);
        if (hi - lo >= v.spacing()) {
            const double d = v.spacing() + lambda;
            const bool rising = w.cosine(hi) >= w.cosine(lo);
            const double a0 = rising ? hi - d : lo - lambda, a1 = rising ? hi + lambda : lo + d;
            double corners = 1.0;
            bool above = true;
            for (const double a : {a0, a1})
                for (const double c : {-lambda, lambda}) {
                    const double h = w.h0 + w.ha * a + w.hc * c;
                    above = above && h >= 0.0;
                    corners = std::min(corners, h / std::sqrt(a * a + c * c + h * h));
                }
            const double nearest = leastLength(w, a0, a1);
            const double across = nearest > crossMove ? crossMove / (nearest - crossMove) : 2.0;
            least = above ? corners : std::max(std::min(w.cosine(a0), w.cosine(a1)) - across, -1.0);
        }
    }
    return {most, least};
}

// The cosine-weighted visible arc between horizon angles h1 <= h2 from v, for a normal at
// angle g in the slice (the shader's aoArc).
double visibleArc(double h1, double h2, double g) {
    return 0.25 * (-std::cos(2.0 * h1 - g) + std::cos(g) + 2.0 * h1 * std::sin(g)) +
           0.25 * (-std::cos(2.0 * h2 - g) + std::cos(g) + 2.0 * h2 * std::sin(g));
}

// One slice at screen angle phi: its open arcs and the occlusion for the least and the most
// horizons.
struct SliceOcclusion {
    double open = 0.0, least = 0.0, most = 0.0;
};

SliceOcclusion obliqueSlice(glm::dvec3 p, glm::dvec3 n, double phi, const WallPlane& wall, const WallView& v) {
    const glm::dvec3 dir(std::cos(phi), std::sin(phi), 0.0), view(0.0, 0.0, 1.0);
    const glm::dvec3 axis = glm::normalize(glm::cross(dir, view));
    const glm::dvec3 projected = n - axis * glm::dot(n, axis);
    const double weight = glm::length(projected);
    if (!(weight > 0.0)) return {};
    const glm::dvec3 np = projected / weight;
    const double g = (glm::dot(np, glm::cross(view, axis)) < 0.0 ? -1.0 : 1.0) * std::acos(std::clamp(glm::dot(np, view), -1.0, 1.0));
    double most[2], least[2];
    for (int side = 0; side < 2; ++side) {
        const double sgn = side == 0 ? -1.0 : 1.0;
        const glm::dvec2 u = sgn * glm::dvec2(dir), across(-u.y, u.x);
        std::tie(most[side], least[side]) = horizonWindow(wall.line(p, u, across), v);
    }
    const auto occluded = [&](const double best[2]) {
        const double h0 = std::max(-std::acos(best[0]), g - 0.5 * kPi);
        const double h1 = std::min(std::acos(best[1]), g + 0.5 * kPi);
        const double open = weight * visibleArc(g - 0.5 * kPi, g + 0.5 * kPi, g);
        return open - weight * visibleArc(h0, h1, g);
    };
    return {weight * visibleArc(g - 0.5 * kPi, g + 0.5 * kPi, g), occluded(least), occluded(most)};
}

// Mean over the nodes and total variation over the circle (5 % added, as in integrateSlices).
struct Averaged {
    double mean = 0.0, variation = 0.0;
};

Averaged averaged(const std::vector<double>& f) {
    Averaged r;
    for (std::size_t i = 0; i < f.size(); ++i) {
        r.mean += f[i] / double(f.size());
        r.variation += std::abs(f[i] - f[(i + 1) % f.size()]);
    }
    r.variation *= 1.05;
    return r;
}

AoWindow obliqueWindow(glm::dvec3 p, glm::dvec3 n, const WallPlane& wall, const WallView& v, int nodes) {
    std::vector<double> open, least, most;
    for (int i = 0; i < nodes; ++i) {
        const SliceOcclusion s = obliqueSlice(p, n, kPi * (i + 0.5) / nodes, wall, v);
        open.push_back(s.open);
        least.push_back(s.least);
        most.push_back(s.most);
    }
    const double strata = 1.0 / v.slices + 1.0 / nodes;
    const Averaged o = averaged(open), l = averaged(least), m = averaged(most);
    // Floor samples lie on the plane of the G-buffer's normal only up to its half-float
    // rounding (2^-11 relative per component, a tilt of at most about 3.5e-4 rad): a floor
    // sample may then count as a horizon that far above the limit, which moves a slice's
    // occlusion by less than weight x 3.5e-4 (the arc's integrand vanishes at the limit, so
    // far less), and open >= weight (cos g + g sin g >= 1). 1e-3 of the open arcs covers it.
    const double normalRounding = 1e-3;
    const double occludedLo = std::max(l.mean - l.variation * strata, 0.0);
    const double occludedHi = m.mean + m.variation * strata + normalRounding * o.mean;
    return {1.0 - occludedHi / (o.mean - o.variation * strata), 1.0 - occludedLo / (o.mean + o.variation * strata)};
}

} // namespace

TEST_CASE("Horizon AO before a wall seen obliquely matches its slice integral within the sampling bounds", "[ao]") {
    test::AoFixture f;
    const WallView v;
    Scene scene = test::floorScene(20.0);
    // The wall: x in [-5, 5], y in [0, 3], z in [-1, 0]; its face z = 0 looks at the camera.
    const glm::mat4 wallBox = glm::scale(glm::translate(glm::mat4(1.0f), glm::vec3(-5.0f, 0.0f, -1.0f)), glm::vec3(10.0f, 3.0f, 1.0f));
    scene.meshes.push_back({test::cubeMesh(), wallBox, 0, "wall"});
    const glm::vec3 target(0.0f, 0.0f, 0.24f);
    const glm::vec3 back(0.0f, float(std::sin(v.elevation)), float(std::cos(v.elevation)));
    f.render(scene, Camera::orthographic({target + 10.0f * back, target, {0.0f, 1.0f, 0.0f}}, float(v.halfHeight), 1.0f, 1.0f, 30.0f),
             v.size, v.size);
    AmbientOcclusionSettings s;
    s.method = AoMethod::Horizon;
    s.radius = float(v.radius);
    s.rays = 2 * v.slices;
    s.steps = v.steps;
    const Image ao = f.run(scene, s);
    const Image normals = readTexture(f.ctx, f.view.normal);
    WallPlane wall;
    wall.view = glm::dmat4(f.view.camera.view);
    wall.inverse = glm::inverse(wall.view);
    wall.normal = glm::normalize(glm::dmat3(wall.view) * glm::dvec3(0.0, 0.0, 1.0));
    wall.point = glm::dvec3(wall.view * glm::dvec4(0.0, 0.0, 0.0, 1.0));
    const int margin = static_cast<int>(std::ceil(v.reachPixels())) + 2; // every sample inside the image
    WindowTally tally;
    for (int y = margin; y < v.size - margin; ++y)
        for (int x = margin; x < v.size - margin; ++x) {
            const glm::dvec3 world = f.world(x, y);
            if (!f.geometry(x, y) || std::abs(world.y) > 1e-3) continue; // the floor only
            const glm::dvec3 p(f.positions.at(x, y, 0), f.positions.at(x, y, 1), f.positions.at(x, y, 2));
            const glm::dvec3 n = glm::normalize(glm::dvec3(normals.at(x, y, 0), normals.at(x, y, 1), normals.at(x, y, 2)));
            const AoWindow w = obliqueWindow(p, n, wall, v, 1024);
            CAPTURE(x, y, world.z, ao.at(x, y, 0), w.lo, w.hi);
            tally.check(ao.at(x, y, 0), w);
        }
    INFO(tally.summary());
    CHECK(tally.checked > 5000);
    CHECK(tally.occluded > 4000);
    // 1 - AO is up to about 0.5 here. With the weight of every slice taken as 1 (0.64 to 1
    // here) the mean moves by 0.008 and 943 pixels leave their window (at 0.97 r, 320; with
    // g x 0.9, 3694).
    CHECK(tally.halfWidth() < 0.02);
}
