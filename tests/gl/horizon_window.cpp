// The derivation is in horizon_window.hpp.
#include "horizon_window.hpp"

#include "core/sampling.hpp"
#include "shaders/common/common_bindings.h"

#include <catch2/catch.hpp>
#include <glm/gtc/constants.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <utility>
#include <vector>

namespace obscura::test::horizon {

namespace {

constexpr double kPi = glm::pi<double>();
constexpr double kNone = std::numeric_limits<double>::infinity(); // an empty interval's lo

using Interval = std::pair<double, double>;

// The a in [lo, hi] where f(a, 0) >= 0.
Interval nonNegative(const Affine<double>& f, Interval range) {
    const auto [lo, hi] = range;
    if (f.da == 0.0) return f.at >= 0.0 ? range : Interval{kNone, 0.0};
    const double root = -f.at / f.da;
    return f.da > 0.0 ? Interval{std::max(lo, root), hi} : Interval{lo, std::min(hi, root)};
}

// The a in [lo, hi] where |X(a, 0)| <= bound(a, 0): where the bound is >= 0 and, squared, a
// quadratic is <= 0. That set is an interval (|X| is convex in a, the bound affine), so of
// the quadratic's pieces (between its roots, or outside them where the point at infinity of
// the screen line lies inside the ball) at most one meets where the bound is >= 0.
Interval within(const Affine<glm::dvec3>& X, const Affine<double>& bound, Interval range) {
    const double qa = glm::dot(X.da, X.da) - bound.da * bound.da;
    const double qb = 2.0 * (glm::dot(X.at, X.da) - bound.at * bound.da), qc = glm::dot(X.at, X.at) - bound.at * bound.at;
    const double huge = std::numeric_limits<double>::max();
    std::vector<Interval> pieces;
    if (qa == 0.0) {
        if (qb == 0.0) {
            if (qc <= 0.0) pieces.push_back({-huge, huge});
        } else {
            pieces.push_back(qb > 0.0 ? Interval{-huge, -qc / qb} : Interval{-qc / qb, huge});
        }
    } else {
        // The roots without cancellation: with q = -(qb + sign(qb) sqrt(disc)) / 2 they are
        // q / qa and qc / q.
        const double disc = qb * qb - 4.0 * qa * qc;
        if (disc < 0.0) {
            if (qa < 0.0) pieces.push_back({-huge, huge});
        } else {
            const double q = -0.5 * (qb + std::copysign(std::sqrt(disc), qb));
            const double x0 = q / qa, x1 = q != 0.0 ? qc / q : x0;
            const double lo = std::min(x0, x1), hi = std::max(x0, x1);
            if (qa > 0.0) pieces.push_back({lo, hi});
            else {
                pieces.push_back({-huge, lo});
                pieces.push_back({hi, huge});
            }
        }
    }
    const Interval feasible = nonNegative(bound, range);
    Interval found{kNone, 0.0};
    for (const Interval& piece : pieces) {
        const Interval cut{std::max(feasible.first, piece.first), std::min(feasible.second, piece.second)};
        if (!(cut.first <= cut.second)) continue;
        if (found.first <= found.second) throw std::logic_error("a ball's points on a line are not one interval");
        found = cut;
    }
    return found;
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

// The most cosine a sample at a in [lo, hi], |c| <= lambda can give (see the header).
double mostCosine(const FaceSide& s, double lo, double hi, double lambda) {
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
double leastCosine(const FaceSide& s, double lo, double hi, double spacing, double lambda) {
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

// The a at which some sample may lie on the face, in range: w > 0 (in front of the camera),
// every bound and ball relaxed by what c (|c| <= lambda) can change. The bounds' signs and
// mostCosine hold where w > 0 at every c: an interval reaching closer to the camera's plane
// than that is refused rather than bounded wrongly.
Interval possibleOnFace(const FaceSide& s, Interval range, double lambda) {
    range = nonNegative({s.w.at + std::abs(s.w.dc) * lambda, s.w.da, 0.0}, range);
    for (const auto& [f, margin] : s.bounds) range = nonNegative({f.at + std::abs(f.dc) * lambda, f.da, 0.0}, range);
    for (const FaceSide::Ball& b : s.balls) {
        if (!(range.first <= range.second)) break;
        const Affine<double> bound{b.most * (s.w.at + std::abs(s.w.dc) * lambda) + glm::length(b.X.dc) * lambda, b.most * s.w.da, 0.0};
        range = within(b.X, bound, range);
    }
    if (range.first <= range.second && std::min(s.w(range.first, 0.0), s.w(range.second, 0.0)) <= std::abs(s.w.dc) * lambda)
        throw std::logic_error("a face's possible samples reach the camera's plane");
    return range;
}

// The a at which every point within lambda in a and c is on the face, `margin` inside its
// bounds, and inside its balls.
Interval surelyOnFace(const FaceSide& s, Interval range, double lambda) {
    for (const auto& [f, margin] : s.bounds) {
        const Affine<double> inset{f.at - margin * s.w.at, f.da - margin * s.w.da, f.dc - margin * s.w.dc};
        range = nonNegative({inset.at - lambda * (std::abs(inset.da) + std::abs(inset.dc)), inset.da, 0.0}, range);
    }
    for (const FaceSide::Ball& b : s.balls) {
        if (!(range.first <= range.second)) break;
        const double slack = lambda * (b.least * (std::abs(s.w.da) + std::abs(s.w.dc)) + glm::length(b.X.da) + glm::length(b.X.dc));
        range = within(b.X, {b.least * s.w.at - slack, b.least * s.w.da, 0.0}, range);
    }
    return range;
}

// The most and the least horizon cosine the shader can find on one face from one side; -1:
// none. `inside`: how far the screen line stays inside the image, less and more a pixel.
std::pair<double, double> horizonWindow(const FaceSide& s, double reach, Interval inside, const Sampling& sampling) {
    const double lambda = sampling.lambda;
    double most = -1.0, least = -1.0;
    const auto [lo, hi] = possibleOnFace(s, {1.0 - lambda, std::min(reach, inside.second) + lambda}, lambda);
    if (lo <= hi) most = mostCosine(s, lo, hi, lambda);
    std::vector<Interval> pieces{surelyOnFace(s, {1.0, std::min(reach, inside.first)}, lambda)};
    for (const Interval& hole : s.hidden) {
        std::vector<Interval> left;
        for (const Interval& piece : pieces) {
            left.push_back({piece.first, std::min(piece.second, hole.first)});
            left.push_back({std::max(piece.first, hole.second), piece.second});
        }
        pieces = std::move(left);
    }
    for (const auto& [from, to] : pieces)
        if (from <= to) least = std::max(least, leastCosine(s, from, to, reach / sampling.steps, lambda));
    return {most, least};
}

// The cosine-weighted visible arc between horizon angles h1 <= h2 from v, for a normal at
// angle g in the slice (the shader's aoArc).
double visibleArc(double h1, double h2, double g) {
    return 0.25 * (-std::cos(2.0 * h1 - g) + std::cos(g) + 2.0 * h1 * std::sin(g)) +
           0.25 * (-std::cos(2.0 * h2 - g) + std::cos(g) + 2.0 * h2 * std::sin(g));
}

// How far the shader's slice direction may turn from the angle the test computes, in radians.
// Its angle pi (k + u) / N takes three float roundings (pi, the sum, the product) and a
// division, which GLSL 4.50 allows 2.5 ULP: within 8 2^-24 of pi, 1.5e-6. GLSL 4.50 gives sin
// and cos no precision; taking the GL's "about one part in 10^5" for float results as theirs
// too (an assumption, which "sin and cos of the horizon's slice angles are within 1e-5" checks
// on the driver at hand), the direction turns by at most about 1.5e-5. 3e-5 covers both.
constexpr double kAngleError = 3e-5;

// The shader's slice offset u at a G-buffer pixel (GL's rows, up): its noise texel's first
// value (pixelRotation in sampling.glsl, at full resolution the pixel itself).
double sliceOffset(int x, int glY) { return detail::noiseTexel(x & (OBSCURA_NOISE_SIZE - 1), glY & (OBSCURA_NOISE_SIZE - 1)).x; }

// The least and the most horizon cosine each side of the slice at screen angle phi can find
// (side 0 toward -dir), for samples up to sampling.lambda pixels from where the test puts them.
struct SideHorizons {
    double least[2] = {-1.0, -1.0}, most[2] = {-1.0, -1.0};
};

SideHorizons sideHorizons(const FloorPixel& px, double phi, const std::vector<Face>& faces, const ScreenRays& rays,
                          const Sampling& sampling) {
    const glm::dvec2 dir(std::cos(phi), std::sin(phi));
    SideHorizons h;
    for (int side = 0; side < 2; ++side) {
        const glm::dvec2 u = (side == 0 ? -1.0 : 1.0) * dir;
        const Interval inside{rays.inside(px.centre, u, 1.0), rays.inside(px.centre, u, -1.0)};
        for (const Face& face : faces) {
            const auto [m, l] = horizonWindow(rays.side(face, px.p, px.v, sampling.radius, px.centre, u), px.reach, inside, sampling);
            h.most[side] = std::max(h.most[side], m);
            h.least[side] = std::max(h.least[side], l);
        }
    }
    return h;
}

// One slice at screen angle phi with the horizons h: its open arcs and the occlusion for the
// least and the most horizons.
struct SliceOcclusion {
    double open = 0.0, least = 0.0, most = 0.0;
};

SliceOcclusion sliceOcclusion(const FloorPixel& px, double phi, const SideHorizons& h) {
    const glm::dvec3 dir(std::cos(phi), std::sin(phi), 0.0);
    const glm::dvec3 axis = glm::normalize(glm::cross(dir, px.v));
    const glm::dvec3 projected = px.n - axis * glm::dot(px.n, axis);
    const double weight = glm::length(projected);
    if (!(weight > 0.0)) return {};
    const glm::dvec3 np = projected / weight;
    const double g = (glm::dot(np, glm::cross(px.v, axis)) < 0.0 ? -1.0 : 1.0) * std::acos(std::clamp(glm::dot(np, px.v), -1.0, 1.0));
    const double open = weight * visibleArc(g - 0.5 * kPi, g + 0.5 * kPi, g);
    const auto occluded = [&](const double best[2]) {
        const double h0 = std::max(-std::acos(best[0]), g - 0.5 * kPi);
        const double h1 = std::min(std::acos(best[1]), g + 0.5 * kPi);
        return open - weight * visibleArc(h0, h1, g);
    };
    return {open, occluded(h.least), occluded(h.most)};
}

} // namespace

Face viewFace(const glm::dmat4& view, glm::dvec3 normal, glm::dvec3 point, const std::vector<Face::Bound>& bounds) {
    const glm::dmat4 inverseView = glm::inverse(view);
    const glm::dmat3 rotation(inverseView);
    const glm::dvec3 translation(inverseView[3]);
    Face face;
    face.normal = glm::normalize(glm::dmat3(view) * normal);
    face.point = glm::dvec3(view * glm::dvec4(point, 1.0));
    for (const Face::Bound& b : bounds) // g . (R o + t) + offset
        face.bounds.push_back({glm::transpose(rotation) * b.gradient, glm::dot(b.gradient, translation) + b.offset, b.margin});
    return face;
}

double FaceSide::cosine(double a, double c) const {
    const glm::dvec3 x = V(a, c);
    return glm::dot(x, v) / glm::length(x);
}

ScreenRays::ScreenRays(const Camera& camera, int width, int height)
    : inverseProjection(glm::inverse(glm::dmat4(camera.projection))), perspective(camera.projection[2][3] == -1.0f),
      size(width, height) {}

std::pair<glm::dvec3, glm::dvec3> ScreenRays::ray(glm::dvec2 s) const {
    // Two points of the pixel's ray at fixed NDC depths (so affine in s) that lie inside the
    // view volume whatever the depth mode: [-1, 1] or [0, 1], reversed, an infinite far plane.
    const glm::dvec2 ndc = 2.0 * s / size - 1.0;
    const auto at = [&](double z) {
        const glm::dvec4 h = inverseProjection * glm::dvec4(ndc, z, 1.0);
        return glm::dvec3(h) / h.w;
    };
    const glm::dvec3 a = at(0.25), b = at(0.75);
    // The direction points away from the camera (view z falls).
    const glm::dvec3 nearer = a.z > b.z ? a : b, farther = a.z > b.z ? b : a;
    return perspective ? std::pair{glm::dvec3(0.0), farther} : std::pair{nearer, farther - nearer};
}

double ScreenRays::inside(glm::dvec2 centre, glm::dvec2 u, double inset) const {
    double reach = std::numeric_limits<double>::max();
    for (int axis = 0; axis < 2; ++axis) {
        if (u[axis] > 0.0) reach = std::min(reach, (size[axis] - inset - centre[axis]) / u[axis]);
        if (u[axis] < 0.0) reach = std::min(reach, (inset - centre[axis]) / u[axis]);
    }
    return reach;
}

FaceSide ScreenRays::side(const Face& face, glm::dvec3 p, glm::dvec3 v, double radius, glm::dvec2 centre, glm::dvec2 u) const {
    // V = w (o - p) and w o at screen position s; every other affine quantity follows from them.
    const auto at = [&](glm::dvec2 s) {
        const auto [origin, direction] = ray(s);
        const double w = -glm::dot(face.normal, direction);
        const glm::dvec3 V = (origin - p) * w - direction * glm::dot(face.normal, face.point - origin);
        return std::pair{V, w};
    };
    const auto [V0, w0] = at(centre);
    const auto [Va, wa] = at(centre + u);
    const auto [Vc, wc] = at(centre + glm::dvec2(-u.y, u.x));
    FaceSide s;
    s.V = {V0, Va - V0, Vc - V0};
    s.w = {w0, wa - w0, wc - w0};
    s.v = v;
    const Affine<glm::dvec3> wo{s.V.at + s.w.at * p, s.V.da + s.w.da * p, s.V.dc + s.w.dc * p};
    for (const Face::Bound& b : face.bounds) {
        const auto f = [&](const glm::dvec3& x, double weight) { return glm::dot(b.gradient, x) + b.offset * weight; };
        s.bounds.push_back({{f(wo.at, s.w.at), f(wo.da, s.w.da), f(wo.dc, s.w.dc)}, b.margin});
    }
    for (const auto& [lo, hi] : face.holes) { // the slab method, the rectangle grown by a pixel
        Interval t{-std::numeric_limits<double>::max(), std::numeric_limits<double>::max()};
        for (int axis = 0; axis < 2; ++axis) {
            const double from = lo[axis] - 1.0 - centre[axis], to = hi[axis] + 1.0 - centre[axis];
            if (u[axis] == 0.0) {
                if (from > 0.0 || to < 0.0) t = {kNone, 0.0};
                continue;
            }
            const double t0 = from / u[axis], t1 = to / u[axis];
            t = {std::max(t.first, std::min(t0, t1)), std::min(t.second, std::max(t0, t1))};
        }
        if (t.first <= t.second) s.hidden.push_back(t);
    }
    // The radius test compares float lengths: 1e-5 relative either way.
    s.balls.push_back({s.V, radius * (1.0 - 1e-5), radius * (1.0 + 1e-5)});
    if (face.discOuter > 0.0)
        s.balls.push_back({{wo.at - s.w.at * face.discCentre, wo.da - s.w.da * face.discCentre, wo.dc - s.w.dc * face.discCentre},
                           face.discInner,
                           face.discOuter});
    return s;
}

std::optional<FloorPixel> floorPixel(const AoFixture& f, const Image& normals, int x, int y, double radius) {
    if (!f.geometry(x, y)) return std::nullopt;
    const glm::dmat4 projection(f.view.camera.projection), view(f.view.camera.view);
    FloorPixel px;
    px.p = glm::dvec3(f.positions.at(x, y, 0), f.positions.at(x, y, 1), f.positions.at(x, y, 2));
    px.n = glm::normalize(glm::dvec3(normals.at(x, y, 0), normals.at(x, y, 1), normals.at(x, y, 2)));
    if (std::abs(f.world(x, y).y) > 1e-3 || (glm::inverse(glm::dmat3(view)) * px.n).y < 0.9) return std::nullopt;
    const bool perspective = projection[2][3] == -1.0;
    px.v = perspective ? -glm::normalize(px.p) : glm::dvec3(0.0, 0.0, 1.0);
    const int glY = f.positions.height - 1 - y; // Image rows run down, GL's up
    px.centre = {x + 0.5, glY + 0.5};
    px.sliceOffset = sliceOffset(x, glY);
    // The shader's radius in pixels: the projection's y scale over the distance.
    px.reach = radius * 0.5 * f.positions.height * projection[1][1] / (perspective ? -px.p.z : 1.0);
    return px;
}

void checkAffine(const ScreenRays& rays, const Face& face, const FloorPixel& px, double radius) {
    const glm::dvec2 u(std::cos(0.3), std::sin(0.3));
    const FaceSide side = rays.side(face, px.p, px.v, radius, px.centre, u);
    const double a = 40.0, c = -25.0;
    const auto [origin, direction] = rays.ray(px.centre + a * u + c * glm::dvec2(-u.y, u.x));
    const glm::dvec3 o = origin + direction * (glm::dot(face.normal, face.point - origin) / glm::dot(face.normal, direction));
    const double w = side.w(a, c);
    CHECK(glm::length(side.V(a, c) / w - (o - px.p)) <= 1e-9 * glm::length(o - px.p));
    for (std::size_t k = 0; k < face.bounds.size(); ++k) {
        const double f = glm::dot(face.bounds[k].gradient, o) + face.bounds[k].offset;
        CHECK(std::abs(side.bounds[k].first(a, c) / w - f) <= 1e-9 * (glm::length(o) + std::abs(face.bounds[k].offset)));
    }
    if (face.discOuter > 0.0) CHECK(glm::length(side.balls.back().X(a, c) / w - (o - face.discCentre)) <= 1e-9 * glm::length(o));
}

AoWindow obliqueWindow(const FloorPixel& px, const std::vector<Face>& faces, const ScreenRays& rays, const Sampling& sampling) {
    // Left out of the model, both small: the G-buffer's normal is rounded to half floats (a
    // tilt of up to 2^-11 rad), so a floor sample off the slice's plane may pass the shader's
    // plane test and count as a horizon a little above the limit; and positions carry about
    // 1e-6 relative reconstruction error. Either moves a slice's occlusion by a small part of
    // its weight (the arc's integrand vanishes at the limit), and open >= weight (cos g +
    // g sin g >= 1): 1e-3 of the open arcs covers them (a review's simulation of the wall's
    // scene found at most 2.6e-5 of them).
    const double normalRounding = 1e-3;
    // The shader's slice k is at pi (k + u) / N, u this pixel's offset, turned by at most
    // kAngleError. Its samples then lie at most reach kAngleError pixels across the test's line
    // (and less along it): lambda grows by that much. Its weight and g are smooth in the angle,
    // and so are the arcs, even where the horizon is clamped to the normal's hemisphere (the
    // arc's derivative in the horizon angle vanishes at the limit): the open arcs and
    // occlusions are taken at both ends of that turn, and between them they stray from those
    // by second-order terms only. The shader's g is acos of a float dot product, which near
    // g = 0 rounds to about 3.5e-4 rad; that moves only the few slices there, by about 1e-5 of
    // the estimate, within the allowance above.
    Sampling widened = sampling;
    widened.lambda += px.reach * kAngleError;
    double openLo = 0.0, openHi = 0.0, occludedLo = 0.0, occludedHi = 0.0;
    for (int k = 0; k < sampling.slices; ++k) {
        const double phi = kPi * (k + px.sliceOffset) / sampling.slices;
        const SideHorizons h = sideHorizons(px, phi, faces, rays, widened);
        const SliceOcclusion a = sliceOcclusion(px, phi - kAngleError, h), b = sliceOcclusion(px, phi + kAngleError, h);
        openLo += std::min(a.open, b.open);
        openHi += std::max(a.open, b.open);
        occludedLo += std::min(a.least, b.least);
        occludedHi += std::max(a.most, b.most);
    }
    // The estimate is 1 - (sum of occlusion) / (sum of open arcs) over the slices.
    occludedHi += normalRounding * openLo;
    return {1.0 - occludedHi / openLo, 1.0 - std::max(occludedLo, 0.0) / openHi};
}

void WindowTally::check(double value, AoWindow w) {
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

std::string WindowTally::summary() const {
    std::ostringstream out;
    out << "mean error " << meanError / checked << " from the window's centre over " << checked << " floor pixels; "
        << occluded << " of them occluded, their window +-" << halfWidth();
    return out.str();
}

} // namespace obscura::test::horizon
