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
#include <stdexcept>
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

// The least and the most sin^2 e the shader can find in the directions of an arc [lo, hi]
// (narrower than pi). In one direction its j-th depth sample is the pixel holding the point at
// (j + jitter) * spacing along it (the offset rounded per axis from the pixel's centre); the
// box's edges lie on pixel edges, so a sample is on the top exactly when that point is inside
// the footprint. The nearest such sample lies within a spacing past the entry, when the chord
// is at least a spacing long, and every one lies at least the entry away; a pixel's centre is
// at most half a pixel's diagonal (lambda) from the point it holds. Both bounds are monotone in
// the entry distance: over the arc the most is at the least entry distance of the directions
// that meet the footprint, and the least is 0 if a direction misses it or crosses it along
// less than a spacing, else at the largest entry distance. Between consecutive candidate
// angles (the arc's ends, the directions of the footprint's corners and the four axes, the
// perpendiculars to its sides) a ray enters and leaves through fixed sides, where the entry
// distance d / cos(phi - alpha) is convex in phi (least at the perpendicular alpha, largest
// at an end) and the chord is convex (opposite sides: least at the perpendicular) or monotone
// (adjacent sides). So the extremes over the arc are at candidates; where the directions that
// meet the footprint end inside the arc they end at a corner, which every such ray meets, at
// most its distance away.
struct Sin2Range {
    double least = 0.0, most = 0.0;
};

Sin2Range sin2Range(double x, double z, double lo, double hi, const BoxView& v) {
    struct Candidate {
        double angle;
        const glm::dvec2* corner;
    };
    const glm::dvec2 corners[4] = {{-v.b, -v.b}, {v.b, -v.b}, {v.b, v.b}, {-v.b, v.b}};
    std::vector<Candidate> candidates = {{lo, nullptr}, {hi, nullptr}};
    const auto add = [&](double angle, const glm::dvec2* corner) {
        const double a = lo + std::fmod(std::fmod(angle - lo, 2.0 * kPi) + 2.0 * kPi, 2.0 * kPi); // in [lo, lo + 2 pi)
        if (a <= hi) candidates.push_back({a, corner});
    };
    for (const glm::dvec2& c : corners) add(std::atan2(c.y - z, c.x - x), &c);
    for (int axis = 0; axis < 4; ++axis) add(0.5 * kPi * axis, nullptr);
    double leastIn = 1e30, mostIn = 0.0, leastChord = 1e30;
    bool all = true, any = false;
    for (const Candidate& c : candidates) {
        Crossing crossing = crossFootprint(x, z, {std::cos(c.angle), std::sin(c.angle)}, v.b);
        if (c.corner) { // it meets the footprint at the corner, if only grazing it
            const double toCorner = glm::length(*c.corner - glm::dvec2(x, z));
            crossing = crossing.hit ? Crossing{true, std::min(crossing.in, toCorner), crossing.out}
                                    : Crossing{true, toCorner, toCorner};
        }
        if (!crossing.hit) {
            all = false;
            continue;
        }
        any = true;
        leastIn = std::min(leastIn, crossing.in);
        mostIn = std::max(mostIn, crossing.in);
        leastChord = std::min(leastChord, crossing.out - crossing.in);
    }
    const double lambda = v.lambda();
    Sin2Range r;
    if (any) r.most = sin2Elevation(std::max(leastIn - lambda, 0.0), v);
    if (all && leastChord >= v.spacing()) r.least = sin2Elevation(mostIn + v.spacing() + lambda, v);
    return r;
}

// The horizontal distance from (x, z) to the box's footprint.
double footprintDistance(double x, double z, const BoxView& v) {
    return std::hypot(std::max(std::abs(x) - v.b, 0.0), std::max(std::abs(z) - v.b, 0.0));
}

// The range of the shader's AO at floor point (x, z). Its slices are phi_k = pi (k + u) / slices
// for one offset u per pixel, each with the directions phi_k and phi_k + pi: in each stratum
// [pi k, pi (k + 1)] / slices (widened by 1e-6 for the shader's float angles) a slice's
// occlusion, the mean of its sides' sin^2 e, lies within the range of that mean over the
// stratum, so the estimate lies within the mean over the strata of those ranges.
struct AoWindow {
    double lo = 1.0, hi = 1.0;
};

AoWindow aoWindow(double x, double z, const BoxView& v) {
    // No point of the top within the radius, however the pixels round: exactly open.
    const double reachable = std::max(footprintDistance(x, z, v) - v.lambda(), 0.0);
    if (reachable * reachable + v.h * v.h > v.radius * v.radius) return {};
    double least = 0.0, most = 0.0;
    for (int k = 0; k < v.slices; ++k) {
        const double lo = kPi * k / v.slices - 1e-6, hi = kPi * (k + 1) / v.slices + 1e-6;
        const Sin2Range ahead = sin2Range(x, z, lo, hi, v), behind = sin2Range(x, z, lo + kPi, hi + kPi, v);
        least += 0.5 * (ahead.least + behind.least) / v.slices;
        most += 0.5 * (ahead.most + behind.most) / v.slices;
    }
    return {1.0 - most, 1.0 - least};
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
    WindowTally tally;
    for (int y = 0; y < v.size; ++y)
        for (int x = 0; x < v.size; ++x) {
            const glm::dvec3 p = f.world(x, y);
            if (!f.geometry(x, y) || std::abs(p.y) > 1e-3) continue; // the floor only
            // Within two pixels of the box the first samples (at least one pixel out) may
            // already be on it.
            if (footprintDistance(p.x, p.z, v) < 2.0 * v.pixel()) continue;
            const AoWindow w = aoWindow(p.x, p.z, v);
            CAPTURE(x, y, p.x, p.z, ao.at(x, y, 0), w.lo, w.hi);
            tally.check(ao.at(x, y, 0), w);
        }
    INFO(tally.summary());
    // Measured when written, each a shader change then undone: hits beyond 0.97 r dropped
    // put 837 pixels outside their windows, slice angles over [0, pi / 2) only 7115.
    CHECK(tally.checked > 5000);
    CHECK(tally.occluded > 1000);
    CHECK(tally.halfWidth() < 0.015); // 1 - AO reaches about 0.3 beside the box
}

// A floor before a wall, seen obliquely from the front, orthographic and in perspective: the
// view direction leans 40 degrees below the horizontal, so the floor's normal leans out of most
// slice planes (weight < 1, g != 0, both varying with the slice's angle); in perspective v and
// the radius in pixels also vary from pixel to pixel.
//
// The shader's estimate, per slice: on each side, the largest cos(angle to v) among its depth
// samples that are above the floor's plane and within r gives the horizon; the arcs of the
// slice follow from it, the weight and g. For a floor point p, the samples above its plane are
// on the wall's face (the floor's are on the plane itself). Let a be a screen position's offset
// from p's pixel centre along the slice's direction and c across it (pixels). The ray through
// it meets the face's plane at o with o - p = V / w, where V, w > 0 and Y = w y(o) (y the world
// height) are affine in (a, c): a ray's origin and direction are affine in the screen position
// and one of them is constant (orthographic: the direction; perspective: the origin). The
// cosine is V.v / |V|, a function of V's direction only, and:
// - on c = 0, V stays in the slice's plane (it holds v and V(0, 0), which is parallel to v), so for
//   a > 0 its direction turns one way and the cosine is monotone in a;
// - {cos >= k}, k >= 0, is {V.v >= k |V|}: convex in (a, c), so on a rectangle where V.v >= 0
//   the least cosine is at a corner;
// - in the slice plane's coordinates (alpha, beta) = (V.e1, V.v), beta / |(alpha, beta)| is the
//   sine of an angle that is largest at a vertex of a parallelogram (the image of a rectangle)
//   lying at alpha > 0; the distance gamma = V.e3 from the plane only lowers a positive cosine
//   (a negative one it raises by at most gamma^2 / (2 |(alpha, beta)|^2)).
// A sample is taken at a_j = max((j + jitter) reach / steps, 1) and rounded to a pixel, which
// moves it by at most lambda (half a pixel's diagonal, with float rounding: 0.72) in a and in c.
// So (horizonWindow):
// - the most any sample gives is at most the largest over the parallelogram of the a the
//   samples can reach with |c| <= lambda, feasibility relaxed by what c can change;
// - the least: where any rounding of the line's points keeps them on the face and within r, an
//   interval of a at least a sample spacing long within [1, reach] holds a sample (unclamped,
//   j < steps), near its end where the cosine is larger; its cosine is at least the least over
//   the rectangle it can be rounded into. Shorter, no sample need land there.
// The slice's occlusion is monotone in each side's horizon, so these give its window; the
// estimate (sum of occlusion over sum of open arcs over the slices) follows from the sums over
// the strata: each within its mean over the slice angles plus the variation over the strata
// (in each stratum one slice, anywhere in it).
namespace {

struct WallView {
    double elevation = glm::radians(40.0); // of the view direction below the horizontal
    double halfHeight = 0.6;               // of the view at the target, world units
    double distance = 3.0;                 // from the target to the eye, world units
    int size = 256;
    double radius = 0.4;
    int slices = 128, steps = 128;
    double lambda = 0.72; // pixels: sqrt(1/2) and float rounding
};

// An affine function of the screen offsets (a, c).
template <class T> struct Affine {
    T at, da, dc;
    T operator()(double a, double c) const { return at + a * da + c * dc; }
};

// The wall's face seen from p along one side of one slice (see above), and v.
struct WallSide {
    Affine<glm::dvec3> V;
    Affine<double> w, Y;
    glm::dvec3 v;

    double cosine(double a, double c) const {
        const glm::dvec3 x = V(a, c);
        return glm::dot(x, v) / glm::length(x);
    }
};

// The camera and the wall's face plane, in view space.
struct WallScene {
    glm::dmat4 inverseProjection, inverseView;
    bool perspective = false;
    int size = 0;
    glm::dvec3 normal, point; // the face's plane; the normal faces the camera

    // The ray through screen position s (GL pixels, y up): origin and direction, each affine in s.
    std::pair<glm::dvec3, glm::dvec3> ray(glm::dvec2 s) const {
        const glm::dvec2 ndc = 2.0 * s / double(size) - 1.0;
        const glm::dvec4 nearH = inverseProjection * glm::dvec4(ndc, -1.0, 1.0);
        const glm::dvec4 farH = inverseProjection * glm::dvec4(ndc, 1.0, 1.0);
        const glm::dvec3 nearPoint = glm::dvec3(nearH) / nearH.w, farPoint = glm::dvec3(farH) / farH.w;
        return perspective ? std::pair{glm::dvec3(0.0), farPoint} : std::pair{nearPoint, farPoint - nearPoint};
    }

    // V, w and Y at screen position s, for p.
    std::tuple<glm::dvec3, double, double> at(glm::dvec3 p, glm::dvec2 s) const {
        const auto [origin, direction] = ray(s);
        const double w = -glm::dot(normal, direction);
        const glm::dvec3 V = (origin - p) * w - direction * glm::dot(normal, point - origin);
        const glm::dvec4 worldY(inverseView[0][1], inverseView[1][1], inverseView[2][1], inverseView[3][1]);
        return {V, w, glm::dot(glm::dvec3(worldY), w * p + V) + worldY.w * w};
    }

    WallSide side(glm::dvec3 p, glm::dvec3 v, glm::dvec2 centre, glm::dvec2 u) const {
        const auto [V0, w0, Y0] = at(p, centre);
        const auto [Va, wa, Ya] = at(p, centre + u);
        const auto [Vc, wc, Yc] = at(p, centre + glm::dvec2(-u.y, u.x));
        return {{V0, Va - V0, Vc - V0}, {w0, wa - w0, wc - w0}, {Y0, Ya - Y0, Yc - Y0}, v};
    }
};

// The a in [lo, hi] where f(a, 0) >= 0.
std::pair<double, double> nonNegative(const Affine<double>& f, double lo, double hi) {
    if (f.da == 0.0) return f.at >= 0.0 ? std::pair{lo, hi} : std::pair{1.0, 0.0};
    const double root = -f.at / f.da;
    return f.da > 0.0 ? std::pair{std::max(lo, root), hi} : std::pair{lo, std::min(hi, root)};
}

// The a in [lo, hi] where |V(a, 0)| <= bound(a, 0): where the bound is >= 0 and, squared, a
// quadratic is <= 0. Its leading coefficient |V_a|^2 - bound_a^2 is positive here (the face
// moves along the line far faster than r w changes), so that is between its roots.
std::pair<double, double> within(const Affine<glm::dvec3>& V, const Affine<double>& bound, double lo, double hi) {
    const double qa = glm::dot(V.da, V.da) - bound.da * bound.da;
    const double qb = 2.0 * (glm::dot(V.at, V.da) - bound.at * bound.da), qc = glm::dot(V.at, V.at) - bound.at * bound.at;
    if (!(qa > 0.0)) throw std::logic_error("the radius bound is not between two roots");
    const double disc = qb * qb - 4.0 * qa * qc;
    if (disc < 0.0) return {1.0, 0.0};
    const double root = std::sqrt(disc);
    const auto [l, h] = nonNegative(bound, lo, hi);
    return {std::max(l, (-qb - root) / (2.0 * qa)), std::min(h, (-qb + root) / (2.0 * qa))};
}

// The least |V(a, 0)| over [lo, hi] (convex in a).
double leastLength(const Affine<glm::dvec3>& V, double lo, double hi) {
    const double vertex = std::clamp(-glm::dot(V.at, V.da) / glm::dot(V.da, V.da), lo, hi);
    return std::min({glm::length(V(lo, 0.0)), glm::length(V(hi, 0.0)), glm::length(V(vertex, 0.0))});
}

// The distance from the origin to the segment x -> y.
double segmentDistance(glm::dvec2 x, glm::dvec2 y) {
    const glm::dvec2 d = y - x;
    const double t = glm::dot(d, d) > 0.0 ? std::clamp(-glm::dot(x, d) / glm::dot(d, d), 0.0, 1.0) : 0.0;
    return glm::length(x + t * d);
}

// The most cosine a sample at a in [lo, hi], |c| <= lambda can give (see above).
double mostCosine(const WallSide& s, double lo, double hi, double lambda) {
    const glm::dvec3 e1 = glm::normalize(s.V.da - glm::dot(s.V.da, s.v) * s.v), e3 = glm::cross(e1, s.v);
    glm::dvec2 corner[4];
    double best = -1.0, gamma = 0.0;
    int k = 0;
    for (const double a : {lo, hi})
        for (const double c : {-lambda, lambda}) {
            const glm::dvec3 x = s.V(a, c);
            corner[k] = {glm::dot(x, e1), glm::dot(x, s.v)};
            if (!(corner[k].x > 0.0)) return 1.0; // not one side of v: no bound
            best = std::max(best, corner[k].y / glm::length(corner[k]));
            gamma = std::max(gamma, std::abs(glm::dot(x, e3)));
            ++k;
        }
    if (best >= 0.0) return best;
    const double nearest = std::min({segmentDistance(corner[0], corner[1]), segmentDistance(corner[1], corner[3]),
                                     segmentDistance(corner[3], corner[2]), segmentDistance(corner[2], corner[0])});
    return std::min(best + 0.5 * gamma * gamma / (nearest * nearest), 1.0);
}

// The least cosine of a sample that the interval [lo, hi] (robustly feasible) must hold; -1:
// none need land there. Where the rectangle's corners have V.v < 0, the cosine on c = 0 less
// its change across c: V moves by at most lambda |V_c|, and unit vectors along x and y differ
// by at most |x - y| / sqrt(|x| |y|).
double leastCosine(const WallSide& s, double lo, double hi, double spacing, double lambda) {
    if (hi - lo < spacing) return -1.0;
    const bool rising = s.cosine(hi, 0.0) >= s.cosine(lo, 0.0);
    const double a0 = rising ? hi - spacing - lambda : lo - lambda, a1 = rising ? hi + lambda : lo + spacing + lambda;
    double corners = 1.0;
    bool front = true;
    for (const double a : {a0, a1})
        for (const double c : {-lambda, lambda}) {
            front = front && glm::dot(s.V(a, c), s.v) >= 0.0;
            corners = std::min(corners, s.cosine(a, c));
        }
    if (front) return corners;
    const double nearest = leastLength(s.V, a0, a1), move = lambda * glm::length(s.V.dc);
    const double across = nearest > move ? move / (nearest - move) : 2.0;
    return std::max(std::min(s.cosine(a0, 0.0), s.cosine(a1, 0.0)) - across, -1.0);
}

// The most and the least horizon cosine the shader can find on one side; -1: none. The radius
// test compares float lengths: 1e-5 relative either way.
std::pair<double, double> horizonWindow(const WallSide& s, double reach, const WallView& view) {
    const double lambda = view.lambda, rMost = view.radius * (1.0 + 1e-5), rLeast = view.radius * (1.0 - 1e-5);
    const Affine<glm::dvec3>& V = s.V;
    double most = -1.0;
    {
        // A sample on the face (Y >= 0) within r, with |c| <= lambda: on c = 0, Y >= -|Y_c| lambda
        // and |V| <= r (w + |w_c| lambda) + |V_c| lambda.
        const auto [ylo, yhi] = nonNegative({s.Y.at + std::abs(s.Y.dc) * lambda, s.Y.da, 0.0}, 1.0 - lambda, reach + lambda);
        const Affine<double> bound{rMost * (s.w.at + std::abs(s.w.dc) * lambda) + glm::length(V.dc) * lambda, rMost * s.w.da, 0.0};
        const auto [lo, hi] = within(V, bound, ylo, yhi);
        if (lo <= hi) most = mostCosine(s, lo, hi, lambda);
    }
    double least = -1.0;
    {
        // Every point within lambda in a and c of (a, 0) on the face 1e-3 above the floor (well
        // above the plane test's tolerance) and within r.
        const Affine<double> above{s.Y.at - 1e-3 * s.w.at, s.Y.da - 1e-3 * s.w.da, s.Y.dc - 1e-3 * s.w.dc};
        const auto [ylo, yhi] = nonNegative({above.at - lambda * (std::abs(above.da) + std::abs(above.dc)), above.da, 0.0}, 1.0, reach);
        const double slack = lambda * (rLeast * (std::abs(s.w.da) + std::abs(s.w.dc)) + glm::length(V.da) + glm::length(V.dc));
        const auto [lo, hi] = within(V, {rLeast * s.w.at - slack, rLeast * s.w.da, 0.0}, ylo, yhi);
        least = leastCosine(s, lo, hi, reach / view.steps, lambda);
    }
    return {most, least};
}

// The cosine-weighted visible arc between horizon angles h1 <= h2 from v, for a normal at
// angle g in the slice (the shader's aoArc).
double visibleArc(double h1, double h2, double g) {
    return 0.25 * (-std::cos(2.0 * h1 - g) + std::cos(g) + 2.0 * h1 * std::sin(g)) +
           0.25 * (-std::cos(2.0 * h2 - g) + std::cos(g) + 2.0 * h2 * std::sin(g));
}

// One floor pixel: its view point and normal, v, its pixel centre (GL pixels) and the radius
// in pixels there, as the shader computes them.
struct FloorPixel {
    glm::dvec3 p, n, v;
    glm::dvec2 centre;
    double reach;
};

// One slice at screen angle phi: its open arcs and the occlusion for the least and the most
// horizons.
struct SliceOcclusion {
    double open = 0.0, least = 0.0, most = 0.0;
};

SliceOcclusion obliqueSlice(const FloorPixel& px, double phi, const WallScene& scene, const WallView& view) {
    const glm::dvec3 dir(std::cos(phi), std::sin(phi), 0.0);
    const glm::dvec3 axis = glm::normalize(glm::cross(dir, px.v));
    const glm::dvec3 projected = px.n - axis * glm::dot(px.n, axis);
    const double weight = glm::length(projected);
    if (!(weight > 0.0)) return {};
    const glm::dvec3 np = projected / weight;
    const double g = (glm::dot(np, glm::cross(px.v, axis)) < 0.0 ? -1.0 : 1.0) * std::acos(std::clamp(glm::dot(np, px.v), -1.0, 1.0));
    double most[2], least[2];
    for (int side = 0; side < 2; ++side) {
        const glm::dvec2 u = (side == 0 ? -1.0 : 1.0) * glm::dvec2(dir);
        std::tie(most[side], least[side]) = horizonWindow(scene.side(px.p, px.v, px.centre, u), px.reach, view);
    }
    const double open = weight * visibleArc(g - 0.5 * kPi, g + 0.5 * kPi, g);
    const auto occluded = [&](const double best[2]) {
        const double h0 = std::max(-std::acos(best[0]), g - 0.5 * kPi);
        const double h1 = std::min(std::acos(best[1]), g + 0.5 * kPi);
        return open - weight * visibleArc(h0, h1, g);
    };
    return {open, occluded(least), occluded(most)};
}

// Mean over the nodes and total variation over the circle. The variation measured between
// nodes can only fall short of the true one, by what a function does between two nodes: a
// small share of it where it is monotone between the few angles where the wall's edges or the
// radius cut in; 5 % is added for that (a heuristic: unlike the box's, these functions have no
// candidate angles worked out).
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

AoWindow obliqueWindow(const FloorPixel& px, const WallScene& scene, const WallView& view, int nodes) {
    std::vector<double> open, least, most;
    for (int i = 0; i < nodes; ++i) {
        const SliceOcclusion s = obliqueSlice(px, kPi * (i + 0.5) / nodes, scene, view);
        open.push_back(s.open);
        least.push_back(s.least);
        most.push_back(s.most);
    }
    const double strata = 1.0 / view.slices + 1.0 / nodes;
    const Averaged o = averaged(open), l = averaged(least), m = averaged(most);
    // Left out of the model, both small: the G-buffer's normal is rounded to half floats (a
    // tilt of up to 2^-11 rad), so a floor sample off the slice's plane may pass the shader's
    // plane test and count as a horizon a little above the limit; and positions carry about
    // 1e-6 relative reconstruction error. Either moves a slice's occlusion by a small part of
    // its weight (the arc's integrand vanishes at the limit), and open >= weight (cos g +
    // g sin g >= 1): 1e-3 of the open arcs covers them (a review's simulation of this scene
    // found at most 2.6e-5 of them).
    const double normalRounding = 1e-3;
    const double occludedLo = std::max(l.mean - l.variation * strata, 0.0);
    const double occludedHi = m.mean + m.variation * strata + normalRounding * o.mean;
    return {1.0 - occludedHi / (o.mean - o.variation * strata), 1.0 - occludedLo / (o.mean + o.variation * strata)};
}

} // namespace

TEST_CASE("Horizon AO before a wall seen obliquely matches its slice integral within the sampling bounds", "[ao]") {
    const WallView view;
    Scene scene = test::floorScene(20.0);
    // The wall: x in [-5, 5], y in [0, 3], z in [-1, 0]; its face z = 0 looks at the camera.
    const glm::mat4 wallBox = glm::scale(glm::translate(glm::mat4(1.0f), glm::vec3(-5.0f, 0.0f, -1.0f)), glm::vec3(10.0f, 3.0f, 1.0f));
    scene.meshes.push_back({test::cubeMesh(), wallBox, 0, "wall"});
    const glm::vec3 target(0.0f, 0.0f, 0.24f);
    const glm::vec3 back(0.0f, float(std::sin(view.elevation)), float(std::cos(view.elevation)));
    const LookAt look{target + float(view.distance) * back, target, {0.0f, 1.0f, 0.0f}};
    for (const bool perspective : {false, true}) {
        CAPTURE(perspective);
        test::AoFixture f;
        const float fovy = 2.0f * std::atan(float(view.halfHeight / view.distance));
        f.render(scene,
                 perspective ? Camera::perspective(look, fovy, 1.0f, 0.5f, 30.0f)
                             : Camera::orthographic(look, float(view.halfHeight), 1.0f, 0.5f, 30.0f),
                 view.size, view.size);
        AmbientOcclusionSettings s;
        s.method = AoMethod::Horizon;
        s.radius = float(view.radius);
        s.rays = 2 * view.slices;
        s.steps = view.steps;
        const Image ao = f.run(scene, s);
        const Image normals = readTexture(f.ctx, f.view.normal);
        const glm::dmat4 projection(f.view.camera.projection), viewMatrix(f.view.camera.view);
        WallScene wall;
        wall.inverseProjection = glm::inverse(projection);
        wall.inverseView = glm::inverse(viewMatrix);
        wall.perspective = perspective;
        wall.size = view.size;
        wall.normal = glm::normalize(glm::dmat3(viewMatrix) * glm::dvec3(0.0, 0.0, 1.0));
        wall.point = glm::dvec3(viewMatrix * glm::dvec4(0.0, 0.0, 0.0, 1.0));
        WindowTally tally;
        for (int y = 0; y < view.size; ++y)
            for (int x = 0; x < view.size; ++x) {
                const glm::dvec3 world = f.world(x, y);
                if (!f.geometry(x, y)) continue;
                FloorPixel px;
                px.p = glm::dvec3(f.positions.at(x, y, 0), f.positions.at(x, y, 1), f.positions.at(x, y, 2));
                px.n = glm::normalize(glm::dvec3(normals.at(x, y, 0), normals.at(x, y, 1), normals.at(x, y, 2)));
                // The floor only: its height and its normal (the wall's lowest pixels are within
                // a few mm of the floor's height too).
                if (std::abs(world.y) > 1e-3 || (glm::dmat3(wall.inverseView) * px.n).y < 0.9) continue;
                px.v = perspective ? -glm::normalize(px.p) : glm::dvec3(0.0, 0.0, 1.0);
                px.centre = {x + 0.5, view.size - 1 - y + 0.5}; // Image rows run down, GL's up
                // The shader's radius in pixels: the projection's y scale over the distance.
                px.reach = view.radius * 0.5 * view.size * projection[1][1] / (perspective ? -px.p.z : 1.0);
                // Every sample inside the image (the shader stops a side at the border).
                const double margin = px.reach + 2.0;
                if (px.centre.x < margin || px.centre.y < margin || px.centre.x > view.size - margin || px.centre.y > view.size - margin)
                    continue;
                if (tally.checked == 0) { // V, w and Y are affine in (a, c): a far point agrees
                    const glm::dvec2 u(std::cos(0.3), std::sin(0.3));
                    const WallSide side = wall.side(px.p, px.v, px.centre, u);
                    const auto [V, w, Y] = wall.at(px.p, px.centre + 40.0 * u - 25.0 * glm::dvec2(-u.y, u.x));
                    CHECK(glm::length(side.V(40.0, -25.0) - V) <= 1e-9 * glm::length(V));
                    CHECK(std::abs(side.w(40.0, -25.0) - w) <= 1e-9 * std::abs(w));
                    CHECK(std::abs(side.Y(40.0, -25.0) - Y) <= 1e-9 * glm::length(V));
                }
                const AoWindow w = obliqueWindow(px, wall, view, 1024);
                CAPTURE(x, y, world.z, ao.at(x, y, 0), w.lo, w.hi);
                tally.check(ao.at(x, y, 0), w);
            }
        INFO(tally.summary());
        CHECK(tally.checked > 4000);
        CHECK(tally.occluded > 3000);
        // 1 - AO is up to about 0.5 here. With the weight of every slice taken as 1 (0.64 to 1
        // here) 1954 checks of both views fail; in perspective, with the radius in pixels 10 %
        // short, 1382. Not caught: v = (0, 0, 1) in perspective, at most 5 degrees off over
        // these pixels, moves the mean by only 0.0005 (about any axis, slices cover the same
        // hemisphere; the samples, off the assumed slices then, change little).
        CHECK(tally.halfWidth() < 0.02);
    }
}
