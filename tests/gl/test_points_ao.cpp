// Point-sampled AO (AoMethod::Points, Crytek-style) under a disc and in a box room against its
// own integral.
// Points does not estimate AO_r: it counts the share of sample points behind the depth buffer,
// the points at distance r u^(1/3) (u uniform: a uniform ball's radial law) along cosine-
// weighted directions of the normal's hemisphere. Seen from below, a point above a floor point
// is behind the depth buffer exactly when it lies above the disc's plane and the eye's ray to
// it crosses the disc first (with the default thickness, the radius, any such point is within
// it). Along one direction that set of distances is where a quadratic is negative, so the
// expected share is a mean over directions of closed-form pieces of u = (d / r)^3. Where
// the eye's ray meets the disc's rim the depth buffer's pixels decide, which that bound
// leaves as a window; a second check takes the G-buffer's own pixels as the occluder, which
// leaves only the Monte Carlo error of the expectation.
#include "ao_fixture.hpp"
#include "obscura/assets.hpp"

#include <catch2/catch.hpp>
#include <glm/gtc/constants.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

using namespace obscura;

namespace {

constexpr double kDiscRadius = 1.0, kDiscHeight = 1.0, kRadius = 1.8;
const glm::dvec3 kEye(0.0, 0.5, 3.2);

// The measure of u = (d / r)^3 over the d in [lo, hi] where alpha d^2 + beta d + gamma < 0:
// [lo, hi] is cut at the quadratic's roots and each piece is kept or not by its midpoint.
double belowZeroShare(double alpha, double beta, double gamma, double lo, double hi) {
    std::vector<double> cuts = {lo, hi};
    const auto root = [&](double t) {
        if (t > lo && t < hi) cuts.push_back(t);
    };
    if (std::abs(alpha) <= 1e-12 * (std::abs(beta) + std::abs(gamma))) {
        if (beta != 0.0) root(-gamma / beta);
    } else {
        const double discriminant = beta * beta - 4.0 * alpha * gamma;
        if (discriminant > 0.0) { // the numerically stable pair of roots
            const double q = -0.5 * (beta + std::copysign(std::sqrt(discriminant), beta));
            root(q / alpha);
            if (q != 0.0) root(gamma / q);
        }
    }
    std::sort(cuts.begin(), cuts.end());
    double share = 0.0;
    for (std::size_t i = 0; i + 1 < cuts.size(); ++i) {
        const double m = 0.5 * (cuts[i] + cuts[i + 1]);
        if (alpha * m * m + beta * m + gamma < 0.0) share += std::pow(cuts[i + 1] / kRadius, 3) - std::pow(cuts[i] / kRadius, 3);
    }
    return share;
}

// The expected share of hidden points at floor point p under a disc of radius a: the mean over
// cosine-weighted directions, midpoints of `rings` rings of equal area times 2 `rings` sectors
// of the unit disc lifted to the hemisphere. A point s = p + w d is above the plane for d >
// dMin; the eye's ray crosses the plane at c = eye + (s - eye) A / (s - eye).y, A = h -
// eye.y, and |c.xz| < a is |eye.xz q.y + A q.xz|^2 < a^2 q.y^2 with q = s - eye, linear in d.
double hiddenShare(const glm::dvec3& p, double a, int rings) {
    const double pi = glm::pi<double>(), A = kDiscHeight - kEye.y;
    const glm::dvec3 q0 = p - kEye;
    const glm::dvec2 eye(kEye.x, kEye.z);
    double sum = 0.0;
    for (int i = 0; i < rings; ++i)
        for (int j = 0; j < 2 * rings; ++j) {
            const double rho = std::sqrt((i + 0.5) / rings), phi = pi * (j + 0.5) / rings;
            const glm::dvec3 w(rho * std::cos(phi), std::sqrt(1.0 - rho * rho), rho * std::sin(phi));
            const double dMin = (kDiscHeight - p.y) / w.y;
            if (dMin >= kRadius) continue;
            const glm::dvec2 v0 = eye * q0.y + A * glm::dvec2(q0.x, q0.z), v1 = eye * w.y + A * glm::dvec2(w.x, w.z);
            const double alpha = glm::dot(v1, v1) - a * a * w.y * w.y;
            const double beta = 2.0 * glm::dot(v0, v1) - 2.0 * a * a * q0.y * w.y;
            const double gamma = glm::dot(v0, v0) - a * a * q0.y * q0.y;
            sum += belowZeroShare(alpha, beta, gamma, dMin, kRadius);
        }
    return sum / (2.0 * rings * rings);
}

// The share of `samples` random points (cosine-weighted directions, distance r u^(1/3)) about
// floor point p that the depth buffer hides: as screenHidden (screen_march.glsl) judges, a
// point is hidden when the pixel it projects to shows the disc (the floor's and the sky's
// hide nothing above the floor) and it lies beyond the disc's plane (the default thickness,
// the radius, holds all of the ball). Left out, each below the half float's rounding: points
// within float rounding of a pixel's edge, which may go to either pixel (a share of order
// 1e-6); points within the plane test's tolerance of the disc's plane (about 2e-5 world units:
// a share below 1e-4); the half-float normals' tilt, which scales `behind` but never flips it.
double hiddenByPixels(const test::AoFixture& f, const glm::dvec3& p, int samples, std::uint64_t seed) {
    const glm::dmat4 toClip = glm::dmat4(f.view.camera.projection) * glm::dmat4(f.view.camera.view);
    const int width = f.positions.width, height = f.positions.height;
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> uniform(0.0, 1.0);
    int hidden = 0;
    for (int i = 0; i < samples; ++i) {
        const double rho = std::sqrt(uniform(rng)), phi = 2.0 * glm::pi<double>() * uniform(rng);
        const glm::dvec3 w(rho * std::cos(phi), std::sqrt(1.0 - rho * rho), rho * std::sin(phi));
        const glm::dvec3 s = p + w * (kRadius * std::cbrt(uniform(rng)));
        const glm::dvec4 clip = toClip * glm::dvec4(s, 1.0);
        const glm::dvec2 uv = glm::dvec2(clip) / clip.w * 0.5 + 0.5;
        if (!(clip.w > 0.0) || uv.x < 0.0 || uv.y < 0.0 || uv.x >= 1.0 || uv.y >= 1.0 || s.y <= kDiscHeight) continue;
        const int x = std::min(int(uv.x * width), width - 1), row = height - 1 - std::min(int(uv.y * height), height - 1);
        hidden += f.geometry(x, row) && f.world(x, row).y > 0.5 * kDiscHeight ? 1 : 0; // a disc pixel
    }
    return double(hidden) / samples;
}

} // namespace

TEST_CASE("Points AO under a disc matches its own integral within the pixel and sampling bounds", "[ao]") {
    test::AoFixture f;
    const Scene scene = test::withDisc(test::floorScene(20.0), kDiscRadius, kDiscHeight);
    constexpr int W = 256, H = 256;
    constexpr float fovY = glm::radians(50.0f);
    f.render(scene, Camera::perspective({glm::vec3(kEye), {0.0f, 0.45f, 0.0f}, {0, 1, 0}}, fovY, 1.0f, 0.05f, 200.0f), W, H);
    constexpr int rays = 256;
    AmbientOcclusionSettings s;
    s.method = AoMethod::Points;
    s.radius = static_cast<float>(kRadius);
    s.rays = rays;
    const Image ao = f.run(scene, s);
    // The GPU judges a point by the depth sample of the pixel its projection falls in, whose
    // centre is at most half a pixel away per axis: an angle of at most sqrt(1/2) of the pixel
    // pitch 2 tan(fov / 2) / H. On the disc's plane, seen at the grazing angle asin(A / L) from
    // L away, that moves the crossing point by up to L^2 angle / A; the far rim is at most
    // 3.2 + a (+ 0.1 for that move itself) away horizontally. The 256-gon's edge lies within
    // 1e-4 a of the circle. So the share lies between those of discs that much larger and smaller.
    const double A = kDiscHeight - kEye.y, far = 3.2 + kDiscRadius + 0.1;
    const double rim = (A * A + far * far) * std::sqrt(0.5) * 2.0 * std::tan(0.5 * fovY) / H / A + 1e-4 * kDiscRadius;
    REQUIRE(rim < 0.1);
    constexpr int rings = 128;
    int checked = 0;
    double meanError = 0.0, meanWindow = 0.0, worstQuadrature = 0.0, meanExactError = 0.0;
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) {
            if (!f.geometry(x, y)) continue;
            const glm::dvec3 p = f.world(x, y);
            if (std::abs(p.y) > 1e-3 || std::hypot(p.x, p.z) > 0.4) continue;
            // The quadrature's error, estimated as twice the change from half the rings.
            const double exact = hiddenShare(p, kDiscRadius, rings);
            const double quadrature = 2.0 * std::abs(exact - hiddenShare(p, kDiscRadius, rings / 2));
            worstQuadrature = std::max(worstQuadrature, quadrature);
            const double lo = 1.0 - hiddenShare(p, kDiscRadius + rim, rings) - quadrature;
            const double hi = 1.0 - hiddenShare(p, kDiscRadius - rim, rings) + quadrature;
            // As in the other AO tests: five standard deviations of a mean of `rays` samples
            // in [0, 1] and the half float's rounding. The GPU's samples are a quasi-random
            // set rotated per pixel, not independent: the binomial sigma bounds their error
            // in practice, and the means over the pixels take them as independent (the
            // rotations repeat every 64 pixels, wider than most of the region).
            const double sigma = std::sqrt(std::max({lo * (1.0 - lo), hi * (1.0 - hi), 1.0 / rays}) / rays);
            const double value = ao.at(x, y, 0), tolerance = 5.0 * sigma + std::ldexp(1.0, -12);
            CAPTURE(x, y, value, lo, hi, 1.0 - exact);
            CHECK(value >= lo - tolerance);
            CHECK(value <= hi + tolerance);
            meanError += value - 0.5 * (lo + hi);
            meanWindow += 0.5 * (hi - lo);
            meanExactError += value - (1.0 - exact);
            ++checked;
        }
    CHECK(checked > 100);
    INFO("mean error " << meanError / checked << " from the windows' centres (window +-" << meanWindow / checked
                       << "), " << meanExactError / checked << " from the exact disc's, over " << checked << " pixels; rim window " << rim << ", quadrature error up to " << worstQuadrature);
    CHECK(std::abs(meanError / checked) <=
          meanWindow / checked + 5.0 * 0.5 / std::sqrt(double(rays) * checked) + std::ldexp(1.0, -12));

    // Against the depth buffer's own pixels: five standard deviations of the GPU's and of the
    // expectation's means, per pixel and over the pixels (sigmas as above). Measured when
    // written: distances r u^(1/2) instead of r u^(1/3) fail this mean by 0.0167 against a
    // bound of about 0.0063, and 0.93 r, at -0.0064, is about the least change it detects;
    // the window above is too wide for either.
    constexpr int samples = 16384;
    int compared = 0;
    double pixelError = 0.0, sumSigma2 = 0.0;
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) {
            if (!f.geometry(x, y)) continue;
            const glm::dvec3 p = f.world(x, y);
            if (std::abs(p.y) > 1e-3 || std::hypot(p.x, p.z) > 0.4) continue;
            const double expected = 1.0 - hiddenByPixels(f, p, samples, std::uint64_t(y) * W + std::uint64_t(x));
            const double mu = std::clamp(expected, 1.0 / rays, 1.0 - 1.0 / rays);
            const double sigma2 = mu * (1.0 - mu) * (1.0 / rays + 1.0 / samples);
            const double value = ao.at(x, y, 0);
            CAPTURE(x, y, value, expected);
            CHECK(std::abs(value - expected) <= 5.0 * std::sqrt(sigma2) + std::ldexp(1.0, -12));
            pixelError += value - expected;
            sumSigma2 += sigma2;
            ++compared;
        }
    CHECK(compared > 100);
    INFO("mean error " << pixelError / compared << " from the depth buffer's expectation over " << compared << " pixels");
    CHECK(std::abs(pixelError / compared) <= 5.0 * std::sqrt(sumSigma2) / compared + std::ldexp(1.0, -12));
}

// Points in the box room (builtin_scenes.cpp: the room's inside, 6 x 3 x 6, and a unit box on
// its floor), seen from inside: corners and the box's faces occlude, balls leave the image at
// its borders, the thickness cuts points behind the box and beyond the walls, and the peeled
// back layer bounds what lies behind the box. The expected share judges random points of the
// shader's law as screenHiddenAt does, by the G-buffer's own front and back layers at the
// pixel each projects to, in double: what is left as a window is float rounding and the
// shader's plane tolerance. The layers themselves are checked against the room cast
// analytically first.
namespace {

constexpr double kRoomHalfSide = 3.0, kRoomTop = 3.0, kBlockHalf = 0.5, kBlockTop = 1.0;

// The first surface along a ray from inside the room: distance and normal (toward the eye's
// side), and the nearest surface strictly behind it (the peeled layer): distance and normal,
// infinite where none (behind a wall nothing; behind the box's near face its far face).
struct SurfaceHit {
    double t = std::numeric_limits<double>::infinity();
    glm::dvec3 normal{0.0};
    double back = std::numeric_limits<double>::infinity();
    glm::dvec3 backNormal{0.0};
};

SurfaceHit castInRoom(const glm::dvec3& eye, const glm::dvec3& dir) {
    const glm::dvec3 roomLo(-kRoomHalfSide, 0.0, -kRoomHalfSide), roomHi(kRoomHalfSide, kRoomTop, kRoomHalfSide);
    const glm::dvec3 blockLo(-kBlockHalf, 0.0, -kBlockHalf), blockHi(kBlockHalf, kBlockTop, kBlockHalf);
    SurfaceHit hit;
    double enter = -std::numeric_limits<double>::infinity(), leave = std::numeric_limits<double>::infinity();
    glm::dvec3 enterNormal(0.0), leaveNormal(0.0);
    for (int i = 0; i < 3; ++i) {
        if (dir[i] == 0.0) {
            if (eye[i] < blockLo[i] || eye[i] > blockHi[i]) leave = -1.0; // misses the box's slab
            continue;
        }
        glm::dvec3 axis(0.0);
        axis[i] = dir[i] > 0.0 ? -1.0 : 1.0; // the face's normal toward the eye's side
        const double wall = ((dir[i] > 0.0 ? roomHi[i] : roomLo[i]) - eye[i]) / dir[i];
        if (wall < hit.t) {
            hit.t = wall;
            hit.normal = axis;
        }
        const double a = (blockLo[i] - eye[i]) / dir[i], b = (blockHi[i] - eye[i]) / dir[i];
        if (std::min(a, b) > enter) {
            enter = std::min(a, b);
            enterNormal = axis;
        }
        if (std::max(a, b) < leave) {
            leave = std::max(a, b);
            leaveNormal = axis;
        }
    }
    if (enter > 0.0 && enter <= leave && enter < hit.t) hit = {enter, enterNormal, leave, leaveNormal};
    return hit;
}

// The room's camera: world-space rays through NDC points, view z of world points, and how far
// a point the shader rebuilds from a 32F depth may lie from its surface along the ray
// (depthReconstructionError with a float ulp of a depth in [0, 1]): |z| |o| / |zScale| 2^-23.
struct RoomCamera {
    glm::dmat4 view, toWorld, inverseProjection;
    glm::dvec3 eye;
    double zScale;

    explicit RoomCamera(const Camera& c)
        : view(c.view), toWorld(glm::inverse(view)), inverseProjection(glm::inverse(glm::dmat4(c.projection))),
          eye(toWorld[3]), zScale(depthReconstruction(c).zScale) {}

    glm::dvec3 direction(glm::dvec2 ndc) const {
        const glm::dvec4 q = inverseProjection * glm::dvec4(ndc, 0.5, 1.0);
        return glm::normalize(glm::dmat3(toWorld) * (glm::dvec3(q) / q.w));
    }
    double viewZ(const glm::dvec3& world) const { return (view * glm::dvec4(world, 1.0)).z; }
    double depthError(const glm::dvec3& world) const {
        return std::abs(viewZ(world)) * glm::length(world - eye) / std::abs(zScale) * std::ldexp(1.0, -23);
    }
};

// The G-buffer's front and back layers against the analytic room at every pixel centre. A
// rasterizer may evaluate depth from vertices rounded to its sub-pixel grid
// (GL_SUBPIXEL_BITS), so each layer may hold its surface's depth at a point up to half a step
// off the centre per axis (test_gbuffer.cpp). Depth is affine on a face, so that changes it
// by at most its change over one full step on one axis, which is allowed (along the ray and
// off the plane), plus the reconstruction bound and 1e-5 relative rounding. A rasterizer
// that truncated to the grid (a full step per axis) could exceed this by up to a quarter.
// Pixels where a step reaches another face of either layer are left out.
struct LayerErrors {
    int checked = 0, edges = 0, wrongBack = 0;
    double front = 0.0, back = 0.0, normal = 0.0; // worst shares of the bounds; worst normal error
};

LayerErrors compareLayers(const RoomCamera& room, const Camera& camera, const Image& positions, const Image& normals,
                          const Image& backDepth) {
    const int W = positions.width, H = positions.height;
    GLint subpixelBits = 0;
    glGetIntegerv(GL_SUBPIXEL_BITS, &subpixelBits);
    const double step = std::ldexp(1.0, -std::max(subpixelBits, 0));
    const double clearDepth = depthReconstruction(camera).clearDepth;
    LayerErrors e;
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) {
            const glm::dvec2 ndc = test::pixelNdc(x, y, W, H);
            const glm::dvec3 dir = room.direction(ndc);
            const SurfaceHit hit = castInRoom(room.eye, dir);
            const glm::dvec3 o = room.eye + hit.t * dir, back = room.eye + hit.back * dir;
            const auto plane = [&](const glm::dvec3& n, const glm::dvec3& q) { return glm::dot(n, q); };
            double frontChange = 0.0, backChange = 0.0;
            bool edge = false;
            for (const glm::dvec2 shift : {glm::dvec2(1, 0), glm::dvec2(-1, 0), glm::dvec2(0, 1), glm::dvec2(0, -1)}) {
                const glm::dvec3 d = room.direction(ndc + step * shift * glm::dvec2(2.0 / W, 2.0 / H));
                const SurfaceHit s = castInRoom(room.eye, d);
                const glm::dvec3 so = room.eye + s.t * d, sb = room.eye + s.back * d;
                edge = edge || s.normal != hit.normal || std::abs(plane(hit.normal, so) - plane(hit.normal, o)) > 1e-9 ||
                       std::isfinite(s.back) != std::isfinite(hit.back) ||
                       (std::isfinite(hit.back) && s.backNormal != hit.backNormal);
                frontChange = std::max(frontChange, std::abs(room.viewZ(so) - room.viewZ(o)));
                if (std::isfinite(hit.back)) backChange = std::max(backChange, std::abs(room.viewZ(sb) - room.viewZ(back)));
            }
            if (edge) {
                ++e.edges;
                continue;
            }
            ++e.checked;
            const double dz = std::abs((room.view * glm::dvec4(dir, 0.0)).z); // the ray's view-z slope
            const glm::dvec3 p = test::worldPoint(positions, room.toWorld, x, y);
            const double frontBound = frontChange / dz * std::abs(glm::dot(hit.normal, dir)) + room.depthError(o) +
                                      1e-5 * glm::length(o - room.eye);
            e.front = std::max(e.front, std::abs(plane(hit.normal, p - o)) / frontBound);
            e.normal = std::max(e.normal, glm::length(glm::dmat3(room.toWorld) * test::texel3(normals, x, y) - hit.normal));
            const double d = backDepth.at(x, y, 0);
            if (!std::isfinite(hit.back)) {
                e.wrongBack += d == clearDepth ? 0 : 1;
                continue;
            }
            e.wrongBack += d == clearDepth ? 1 : 0;
            const double backBound = backChange + room.depthError(back) + 1e-5 * std::abs(room.viewZ(back));
            e.back = std::max(e.back, std::abs(viewPositionFromDepth(camera, ndc, d).z - room.viewZ(back)) / backBound);
        }
    return e;
}

// The thickness rules the test runs (screenHiddenAt).
struct ThicknessCase {
    const char* name;
    ScreenThickness mode;
    double thickness; // world units; peeled: where the back layer is empty
};
constexpr std::size_t kThicknessCases = 4;

// Per thickness case, how many of a pixel's sample points are hidden: `lo` those the GPU must
// find hidden, `hi` also those whose verdict rounding could flip.
struct HiddenCounts {
    std::array<int, kThicknessCases> lo{}, hi{};
};

// What screenHiddenAt reads: the G-buffer's layers (view space, row 0 at the top).
struct DepthLayers {
    const Camera& camera;
    const Image &positions, &normals, &backDepth;
    double zScale, clearDepth;

    DepthLayers(const Camera& c, const Image& p, const Image& n, const Image& b)
        : camera(c), positions(p), normals(n), backDepth(b), zScale(depthReconstruction(c).zScale),
          clearDepth(depthReconstruction(c).clearDepth) {}
};

// The hidden points among `samples` random ones about pixel (x, y)'s point p (its normal n, as
// the shader normalizes it; the shader's law: cosine-weighted directions, distance r u^(1/3)),
// each judged as screenHiddenAt judges it at the pixel its projection falls in. In float the
// shader's `behind`, view z and back z differ from these by rounding, at most 1e-5 for
// coordinates up to 10 (about ten ulps); its plane tolerance is 4e-6 max(|o|, |s|) plus two
// reconstruction errors of o (0 to 2 |z| |o| / |zScale| 2^-23). Left out, as under the disc:
// points within float rounding of a pixel's edge, which may go to either pixel (a share of
// order 1e-6).
using ThicknessCases = std::array<ThicknessCase, kThicknessCases>;

HiddenCounts countHidden(const DepthLayers& g, int x, int y, double radius, const ThicknessCases& cases, int samples,
                         std::uint64_t seed) {
    const int W = g.positions.width, H = g.positions.height;
    const glm::dmat4 projection(g.camera.projection);
    const glm::dvec3 p = test::texel3(g.positions, x, y), n = glm::normalize(test::texel3(g.normals, x, y));
    const glm::dvec3 t = glm::normalize(glm::cross(n, std::abs(n.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0)));
    const glm::dvec3 b = glm::cross(n, t);
    constexpr double rounding = 1e-5;
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> uniform(0.0, 1.0);
    HiddenCounts counts;
    for (int k = 0; k < samples; ++k) {
        const double rho = std::sqrt(uniform(rng)), phi = 2.0 * glm::pi<double>() * uniform(rng);
        const glm::dvec3 w = rho * std::cos(phi) * t + rho * std::sin(phi) * b + std::sqrt(1.0 - rho * rho) * n;
        const glm::dvec3 s = p + w * (radius * std::cbrt(uniform(rng)));
        const glm::dvec4 clip = projection * glm::dvec4(s, 1.0);
        if (!(clip.w > 0.0)) continue;
        const glm::dvec2 uv = glm::dvec2(clip) / clip.w * 0.5 + 0.5;
        if (uv.x < 0.0 || uv.y < 0.0 || uv.x >= 1.0 || uv.y >= 1.0) continue; // the border policy
        const int px = std::min(int(uv.x * W), W - 1), row = H - 1 - std::min(int(uv.y * H), H - 1);
        const glm::dvec3 o = test::texel3(g.positions, px, row), on = test::texel3(g.normals, px, row);
        const double behind = -glm::dot(s - o, on);
        const double plane = 4e-6 * std::max(glm::length(o), glm::length(s));
        const double reconstruction = 2.0 * std::abs(o.z) * glm::length(o) / std::abs(g.zScale) * std::ldexp(1.0, -23);
        const bool surelyBehind = behind - rounding > plane + reconstruction, maybeBehind = behind + rounding > plane;
        const double back = g.backDepth.at(px, row, 0);
        const bool peeled = back != g.clearDepth;
        const double limit = peeled ? std::min(viewPositionFromDepth(g.camera, test::pixelNdc(px, row, W, H), back).z, o.z) : 0.0;
        for (std::size_t c = 0; c < kThicknessCases; ++c) {
            const bool slabSure = behind + rounding <= cases[c].thickness, slabMaybe = behind - rounding <= cases[c].thickness;
            const bool layerSure = peeled && s.z - rounding >= limit, layerMaybe = peeled && s.z + rounding >= limit;
            bool surelyInside = slabSure, maybeInside = slabMaybe;
            if (cases[c].mode == ScreenThickness::DepthPeeling && peeled) {
                surelyInside = layerSure;
                maybeInside = layerMaybe;
            } else if (cases[c].mode == ScreenThickness::PeelingOrConstant) {
                surelyInside = slabSure || layerSure;
                maybeInside = slabMaybe || layerMaybe;
            }
            counts.lo[c] += surelyBehind && surelyInside ? 1 : 0;
            counts.hi[c] += maybeBehind && maybeInside ? 1 : 0;
        }
    }
    return counts;
}

} // namespace

TEST_CASE("Points AO in a box room matches its own share of the depth layers within the rounding and sampling bounds", "[ao]") {
    test::AoFixture f;
    const assets::LoadedScene room = assets::builtinScene("box_room");
    constexpr int W = 96, H = 72;
    const Camera camera = assets::makeCamera(room.camera, W, H);
    f.render(room.scene, camera, W, H, 2);
    const Image normals = readTexture(f.ctx, f.view.normal), backDepth = readTexture(f.ctx, f.view.backDepth);

    const LayerErrors layers = compareLayers(RoomCamera(camera), camera, f.positions, normals, backDepth);
    INFO("layers: " << layers.checked << " pixels checked, " << layers.edges
                    << " within a snap step of an edge; worst share of the bound: front " << layers.front << ", back "
                    << layers.back << "; normals up to " << layers.normal << " off; " << layers.wrongBack
                    << " back layers wrongly empty or not");
    REQUIRE(layers.checked > W * H * 9 / 10);
    REQUIRE(layers.front <= 1.0);
    REQUIRE(layers.back <= 1.0);
    REQUIRE(layers.normal <= std::ldexp(1.0, -10)); // half floats: within 2^-12 per component
    REQUIRE(layers.wrongBack == 0);

    constexpr double radius = 0.8;
    constexpr int gpuRays = 256, samples = 4096;
    const ThicknessCases cases = {{{"constant, the radius", ScreenThickness::Constant, radius},
                                   {"constant 0.2", ScreenThickness::Constant, 0.2},
                                   {"peeled, else 0.2", ScreenThickness::DepthPeeling, 0.2},
                                   {"peeled or 0.2", ScreenThickness::PeelingOrConstant, 0.2}}};
    const DepthLayers depthLayers(camera, f.positions, normals, backDepth);
    std::vector<HiddenCounts> expected(std::size_t(W) * H);
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) {
            const std::size_t i = std::size_t(y) * W + std::size_t(x);
            expected[i] = countHidden(depthLayers, x, y, radius, cases, samples, i);
        }

    AmbientOcclusionSettings s;
    s.method = AoMethod::Points;
    s.radius = static_cast<float>(radius);
    s.rays = gpuRays;
    for (std::size_t c = 0; c < cases.size(); ++c) {
        s.thicknessMode = cases[c].mode;
        s.thickness = static_cast<float>(cases[c].thickness);
        const Image ao = f.run(room.scene, s);
        int outside = 0, occluded = 0;
        double meanError = 0.0, meanWindow = 0.0, sumSigma2 = 0.0, meanValue = 0.0;
        double worst = -std::numeric_limits<double>::infinity();
        for (int y = 0; y < H; ++y)
            for (int x = 0; x < W; ++x) {
                const std::size_t i = std::size_t(y) * W + std::size_t(x);
                const double a = 1.0 - double(expected[i].hi[c]) / samples, b = 1.0 - double(expected[i].lo[c]) / samples;
                // Five standard deviations of the GPU's mean of `gpuRays` points and of the
                // expectation's of `samples` (binomial, as under the disc), and the half
                // float's rounding.
                const double mu = std::clamp(0.5 * (a + b), 1.0 / gpuRays, 1.0 - 1.0 / gpuRays);
                const double sigma2 = mu * (1.0 - mu) * (1.0 / gpuRays + 1.0 / samples);
                const double value = ao.at(x, y, 0), slack = 5.0 * std::sqrt(sigma2) + std::ldexp(1.0, -12);
                const double miss = std::max(a - slack - value, value - b - slack);
                worst = std::max(worst, miss);
                outside += miss > 0.0 ? 1 : 0;
                occluded += b < 0.95 ? 1 : 0;
                meanError += value - 0.5 * (a + b);
                meanWindow += 0.5 * (b - a);
                meanValue += value;
                sumSigma2 += sigma2;
            }
        const int n = W * H;
        INFO(cases[c].name << ": " << occluded << " of " << n << " pixels occluded by more than 0.05, " << outside
                           << " outside their window (closest " << -worst << " inside); mean AO " << meanValue / n
                           << ", mean error " << meanError / n << ", window +-" << meanWindow / n);
        CHECK(occluded > n / 10);
        CHECK(outside == 0);
        // The pixels' mean, taking their errors as independent (the per-pixel rotations repeat
        // every 64 pixels; the binomial sigma overstates a rotated Hammersley set's error).
        // Measured when written, each a shader change then undone: the thickness test left out
        // puts 310, 1080 and 358 pixels outside their windows; the back layer left out (0.2
        // everywhere) 16, its mean off by 0.0025 against a bound of 0.0009; 0.2 left out where
        // the back layer is empty 358; distances r u^(1/2) move the three means by 0.0062,
        // 0.0019 and 0.0024 against about 0.001, 0.93 r by 0.0038, 0.0007 and 0.0011 (two
        // caught); 0.98 r, by 0.0010 with the radius, is not caught.
        CHECK(std::abs(meanError / n) <= meanWindow / n + 5.0 * std::sqrt(sumSigma2) / n + std::ldexp(1.0, -12));
    }
}
