// Point-sampled AO (AoMethod::Points, Crytek-style) under a disc against its own integral.
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

#include <catch2/catch.hpp>
#include <glm/gtc/constants.hpp>

#include <algorithm>
#include <cmath>
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
