// Ambient occlusion: closed forms (an open plane, a floor in front of a wall, a disc) and
// stability over sizes, projections and the sky (post-process mode: test_ao_host.cpp; screen
// against voxel space: test_ao_screen_voxel.cpp).
#include "ao_fixture.hpp"

#include "obscura/assets.hpp"
#include "obscura/obscura.hpp"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <vector>

using namespace obscura;
using test::AoFixture;
using test::AoVariant;
using test::discAo;
using test::floorScene;
using test::kAllVariants;
using test::lookAt;
using test::nameOf;
using test::wallMean;

namespace {

constexpr double kPi = 3.14159265358979323846;

// rho(t) of an obscurance falloff (AO: 0, a hit is fully occluded).
double falloffOf(ObscuranceFalloff f, double t) {
    switch (f) {
    case ObscuranceFalloff::Linear: return t;
    case ObscuranceFalloff::Quadratic: return t * t;
    case ObscuranceFalloff::Smooth: return t * t * (3.0 - 2.0 * t);
    case ObscuranceFalloff::None: break;
    }
    return 0.0;
}

// Points: a direction that meets a surface at t < r holds points at distances x = r s with
// density 3 s^2 (uniform in the ball), hidden when x > t; each counts 1 - rho(s). The
// expected occlusion is Integral_{t/r}^1 (1 - rho(s)) 3 s^2 ds, in closed form per falloff
// (Integral_tau^1 3 s^(k+2) ds = 3 (1 - tau^(k+3)) / (k+3)).
double pointsOccluded(ObscuranceFalloff f, double tau) {
    const auto moment = [tau](int k) { return 3.0 * (1.0 - std::pow(tau, k + 3)) / (k + 3); };
    switch (f) {
    case ObscuranceFalloff::Linear: return moment(0) - moment(1);
    case ObscuranceFalloff::Quadratic: return moment(0) - moment(2);
    case ObscuranceFalloff::Smooth: return moment(0) - 3.0 * moment(2) + 2.0 * moment(3);
    case ObscuranceFalloff::None: break;
    }
    return moment(0);
}

// The angle from the floor's normal toward +z, away from the wall, of the bent normal (the
// cosine-weighted mean of the open directions) of a floor point with c = distance / reach:
// over the disc, E[y; open] = (1/2) Integral_{-1}^{c} (1 - u^2) du and E[z; open] =
// 2 (1 - c^2)^{3/2} / (3 pi) for c < 1.
double wallBentTilt(double c) {
    if (c >= 1.0) return 0.0;
    const double y = 0.5 * ((c - c * c * c / 3.0) + 2.0 / 3.0);
    const double z = 2.0 * std::pow(1.0 - c * c, 1.5) / (3.0 * kPi);
    return std::atan2(z, y);
}

// The same for the points method: a direction with component u toward the wall, c = distance /
// radius < u, keeps its point (at distance r s, density 3 s^2) open with probability (c / u)^3,
// which adds (1/2) Integral_c^1 (1 - u^2) (c/u)^3 du = c/4 - c^3/4 + (c^3/2) ln c to E[y] and
// -(2/pi) Integral_c^1 u sqrt(1 - u^2) (c/u)^3 du = -(2 c^3/pi) (sqrt(1 - c^2)/c + asin c - pi/2)
// to E[z].
double pointsBentTilt(double c) {
    if (c >= 1.0) return 0.0;
    const double c3 = c * c * c;
    const double y = 0.5 * ((c - c3 / 3.0) + 2.0 / 3.0) + 0.5 * (0.5 * c - 0.5 * c3 + (c > 0.0 ? c3 * std::log(c) : 0.0));
    const double z = 2.0 * std::pow(1.0 - c * c, 1.5) / (3.0 * kPi) -
                     2.0 / kPi * (c * c * std::sqrt(1.0 - c * c) + c3 * (std::asin(c) - 0.5 * kPi));
    return std::atan2(z, y);
}

} // namespace

TEST_CASE("An open plane gives AO = 1 exactly for every method resolution falloff and projection", "[ao]") {
    AoFixture f;
    const Scene scene = floorScene();
    constexpr int W = 64, H = 48;
    const LookAt look{{0, 3, 6}, {0, 0, 0}, {0, 1, 0}};
    struct Projection {
        const char* name;
        Camera camera;
    };
    const Projection projections[] = {
        {"perspective", lookAt(look.eye, look.target, W, H)},
        {"reversed-Z, infinite far", Camera::perspective(look, glm::radians(50.0f), float(W) / H, 0.05f, INFINITY,
                                                         DepthMode::Reversed)},
        {"orthographic, zero to one", Camera::orthographic(look, 3.0f, float(W) / H, 0.05f, 200.0f,
                                                           DepthMode::StandardZeroToOne)},
        // At 16 degrees, the radius 10 pixels: the horizon method's first depth samples, a
        // pixel or two out and rounded off the slice, found horizons on the floor itself
        // where the half-float normal tilts its tangent plane (AO 0.997; GBufferView::normalError).
        {"orthographic, grazing", Camera::orthographic({{1, 1.5f, 5}, {0, 0, 0}, {0, 1, 0}}, 4.8f, float(W) / H, 0.05f, 100.0f)},
        // Far / near = 1e10 with standard depth: the floor's depths lie within 2e-5 of 1, where
        // a float step (6e-8) spans 0.4 % of the view distance. The tangent-plane tests must
        // allow for that (depthReconstructionError), not find the floor under itself.
        {"perspective, near 1e-4 far 1e6", Camera::perspective(look, glm::radians(50.0f), float(W) / H, 1e-4f, 1e6f)},
    };
    // Every method, the screen methods with depth peeling (alone and with the constant
    // slab) and the other voxel traversals.
    std::vector<AoVariant> variants(std::begin(kAllVariants), std::end(kAllVariants));
    for (const AoVariant more : {AoVariant{AoMethod::RayMarch, ScreenMarch::View, ScreenThickness::DepthPeeling},
                                 AoVariant{AoMethod::RayMarch, ScreenMarch::HiZ, ScreenThickness::DepthPeeling},
                                 AoVariant{AoMethod::Points, ScreenMarch::View, ScreenThickness::DepthPeeling},
                                 AoVariant{AoMethod::RayMarch, ScreenMarch::HiZ, ScreenThickness::PeelingOrConstant},
                                 AoVariant{AoMethod::Points, ScreenMarch::View, ScreenThickness::PeelingOrConstant},
                                 AoVariant{AoMethod::Voxel, ScreenMarch::View, ScreenThickness::Constant, VoxelTraversal::March},
                                 AoVariant{AoMethod::Voxel, ScreenMarch::View, ScreenThickness::Constant, VoxelTraversal::Exact}})
        variants.push_back(more);
    for (const Projection& projection : projections) {
        f.render(scene, projection.camera, W, H, 2); // a back layer for depth peeling
        for (const AoVariant variant : variants)
            for (AoResolution resolution : {AoResolution::Full, AoResolution::Half, AoResolution::Quarter})
                for (ObscuranceFalloff falloff : {ObscuranceFalloff::None, ObscuranceFalloff::Smooth}) {
                    // The horizon method integrates AO only (no falloff).
                    if (variant.method == AoMethod::Horizon && falloff != ObscuranceFalloff::None) continue;
                    CAPTURE(projection.name, nameOf(variant.method), static_cast<int>(variant.march),
                            static_cast<int>(variant.thickness), static_cast<int>(variant.traversal),
                            static_cast<int>(resolution), static_cast<int>(falloff));
                    AmbientOcclusionSettings s = test::settingsOf(variant);
                    s.radius = 2.0f;
                    // Not a power of two: n / n is where a GPU's division by reciprocal (GLSL
                    // allows 2.5 ULP) falls short of 1.
                    s.rays = 24;
                    s.resolution = resolution;
                    s.blurRadius = resolution == AoResolution::Full ? 0 : 2;
                    s.falloff = falloff;
                    VoxelizerSettings v;
                    v.resolution = 64;
                    test::checkOpenEverywhere(f, f.run(scene, s, v));
                }
    }
}

namespace {

struct WallQuantity {
    ObscuranceFalloff falloff;
    bool cosine;
};

// AO or obscurance and the bent normal of the wall scene's floor, as rendered into `f`,
// against their integrals (wallMean) within each method's geometric window and the sampling
// error; radius 1, 32 steps.
void checkWall(AoFixture& f, const Scene& scene, AoMethod method, ScreenMarch march, WallQuantity q, int rays) {
    const int W = f.positions.width, H = f.positions.height;
    const glm::dmat3 toWorld(glm::inverse(glm::dmat4(f.view.camera.view)));
    constexpr double radius = 1.0;
    constexpr int steps = 32;
    const double voxelSide = test::kWallVoxelSide;
    AmbientOcclusionSettings s;
    s.method = method;
    s.march = march;
    s.radius = static_cast<float>(radius);
    s.rays = rays;
    s.steps = steps;
    s.falloff = q.falloff;
    s.cosineWeighted = q.cosine;
    s.bentNormals = true;
    // Points: every point behind the wall within the radius counts as inside it.
    if (method == AoMethod::Points) s.thickness = static_cast<float>(2.0 * radius);
    if (method == AoMethod::Voxel) s.voxels = &f.voxelizer.voxelize(scene, test::wallVoxels());
    const AmbientOcclusionView out = f.ao.run(f.view, s);
    const Image ao = readTexture(f.ctx, out.ao), bent = readTexture(f.ctx, out.bentNormal);
    const auto exact = [&](double d) { return falloffOf(q.falloff, std::min(d / radius, 1.0)); };
    // Ray marching finds a hit at its first sample past it, at most a step (r / steps)
    // late, and none beyond its last sample, at least at r (1 - 1/steps): rho only
    // grows with d, so the value can only be higher. Voxels bring the wall closer by up
    // to a voxel side: lower.
    const auto late = [&](double d) { return falloffOf(q.falloff, std::min((d + radius / steps) / radius, 1.0)); };
    const double marchReach = radius * (1.0 - 1.0 / steps);
    const bool tilted = q.falloff == ObscuranceFalloff::None && q.cosine;
    double meanError = 0.0, meanWindow = 0.0, tiltError = 0.0, tiltWindow = 0.0;
    int checked = 0;
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) {
            glm::dvec3 p;
            if (!test::wallFloorPixel(f, x, y, p)) continue;
            const double distance = p.z + 1.0;
            double lo = wallMean(distance, radius, q.cosine, exact), hi = lo;
            double cLo = distance / radius, cHi = cLo; // the bent normal's window of c
            if (method == AoMethod::RayMarch) {
                hi = wallMean(distance, marchReach, q.cosine, late);
                cHi = distance / marchReach;
            } else if (method == AoMethod::Points) {
                // Each point is classified exactly against the wall's plane: no window.
                lo = hi = wallMean(distance, radius, q.cosine, [&](double t) { return 1.0 - pointsOccluded(q.falloff, t / radius); });
            } else {
                const double closer = std::max(distance - voxelSide, 0.0);
                lo = wallMean(closer, radius, q.cosine, exact);
                cLo = closer / radius;
            }
            // Five standard deviations of the mean of `rays` samples in [0, 1], whose
            // variance is at most mu (1 - mu) (the rotated Hammersley set taken as random:
            // conservative), and the half float's rounding (to nearest: 2^-12 below 1).
            const double sigma = std::sqrt(std::max({lo * (1.0 - lo), hi * (1.0 - hi), 1.0 / rays}) / rays);
            const double value = ao.at(x, y, 0), tolerance = 5.0 * sigma + std::ldexp(1.0, -12);
            CAPTURE(x, y, distance, value, lo, hi);
            CHECK(value >= lo - tolerance);
            CHECK(value <= hi + tolerance);
            meanError += value - 0.5 * (lo + hi);
            meanWindow += 0.5 * (hi - lo);
            if (tilted) {
                const glm::dvec3 b = toWorld * glm::dvec3(bent.at(x, y, 0), bent.at(x, y, 1), bent.at(x, y, 2));
                const double tilt = std::atan2(b.z, b.y);
                const double tiltLo = method == AoMethod::Points ? pointsBentTilt(cLo) : wallBentTilt(cHi);
                const double tiltHi = method == AoMethod::Points ? tiltLo : wallBentTilt(cLo);
                // Normalized in float, stored as half floats that may round each component
                // toward zero by 2^-10 of its size (kHalfNormalError), read back exactly.
                CHECK(std::abs(glm::length(b) - 1.0) < kHalfNormalError + 1e-6);
                // The wall is symmetric in x: 5 sigma of the mean's x over its length,
                // sqrt(E[x^2] = 1/4) / (1/3) / sqrt(rays) each.
                CHECK(std::abs(b.x) < 5.0 * 0.5 * 3.0 / std::sqrt(double(rays)));
                tiltError += tilt - 0.5 * (tiltLo + tiltHi);
                tiltWindow += 0.5 * (tiltHi - tiltLo);
            }
            ++checked;
        }
    CHECK(checked > 200);
    // Per-pixel rotations make each pixel's estimate unbiased and independent: the mean
    // error over the pixels stays within the mean window plus 5 sigma / sqrt(pixels),
    // plus the half-float rounding.
    INFO("mean error " << meanError / checked << " over " << checked << " pixels, window +-" << meanWindow / checked);
    CHECK(std::abs(meanError / checked) <= meanWindow / checked + 5.0 * 0.5 / std::sqrt(double(rays) * checked) + std::ldexp(1.0, -12));
    if (tilted) {
        // The bent normal's angle: the sum of `rays` open directions has per-component
        // standard deviations at most sqrt(E[z^2]) = 1/2 and sqrt(E[y^2]) = sqrt(1/2)
        // over sqrt(rays), and a length of at least E[y] >= 1/3 per ray, so its angle's
        // is at most sqrt(3/4) / (1/3) / sqrt(rays); a mean over the pixels, over
        // sqrt(pixels) more. (The angle of a mean is biased by order sigma^2 per pixel,
        // about 1e-3 rad, well inside that.)
        const double tiltSigma = std::sqrt(0.75) * 3.0 / std::sqrt(double(rays) * checked);
        INFO("bent normal tilt mean error " << tiltError / checked << " rad, window +-" << tiltWindow / checked);
        CHECK(std::abs(tiltError / checked) <= tiltWindow / checked + 5.0 * tiltSigma);
    }
}

} // namespace

TEST_CASE("AO obscurance and the bent normal of a floor in front of a wall match their integrals within the "
          "sampling error", "[ao]") {
    AoFixture f;
    // The wall's plane z = -1 faces the camera; floor points at distance D = z + 1 from it.
    const Scene scene = test::wallScene();
    constexpr int W = 96, H = 72;
    f.render(scene, test::wallCamera(W, H), W, H);
    for (AoMethod method : {AoMethod::RayMarch, AoMethod::Voxel, AoMethod::Points})
        for (const WallQuantity q : {WallQuantity{ObscuranceFalloff::None, true}, WallQuantity{ObscuranceFalloff::None, false},
                                     WallQuantity{ObscuranceFalloff::Linear, true}, WallQuantity{ObscuranceFalloff::Linear, false},
                                     WallQuantity{ObscuranceFalloff::Quadratic, true},
                                     WallQuantity{ObscuranceFalloff::Smooth, true}}) {
            CAPTURE(nameOf(method), static_cast<int>(q.falloff), q.cosine);
            checkWall(f, scene, method, ScreenMarch::View, q, 1024);
        }
}

TEST_CASE("AO and the bent normal of the floor in front of a wall match their integrals in reversed-Z and "
          "orthographic views", "[ao]") {
    // The wall test's closed forms hold for any projection whose depth buffer holds every
    // surface the rays meet: the same view direction with reversed depth and an infinite far
    // plane, and orthographic with [0, 1] and reversed depth. A method that read depth one
    // way only (a standard [-1, 1] linearization, a perspective divide) would be off by far
    // more than the sampling error here, where AO runs from about 0.5 to 1.
    AoFixture f;
    const Scene scene = test::wallScene();
    constexpr int W = 96, H = 72;
    const LookAt look{{0, 2.5f, 3.5f}, {0, 0.3f, -0.6f}, {0, 1, 0}}; // test::wallCamera's
    // Half height: the perspective view's at the target (its distance 4.7 x tan 25 degrees).
    const float halfHeight = 4.7f * std::tan(glm::radians(25.0f));
    struct Projection {
        const char* name;
        Camera camera;
    };
    const Projection projections[] = {
        {"reversed-Z, infinite far", Camera::perspective(look, glm::radians(50.0f), float(W) / H, 0.05f, INFINITY,
                                                         DepthMode::Reversed)},
        {"orthographic, zero to one", Camera::orthographic(look, halfHeight, float(W) / H, 0.05f, 200.0f,
                                                           DepthMode::StandardZeroToOne)},
        {"orthographic, reversed", Camera::orthographic(look, halfHeight, float(W) / H, 0.05f, 200.0f, DepthMode::Reversed)},
    };
    for (const Projection& projection : projections) {
        f.render(scene, projection.camera, W, H);
        for (const AoVariant variant : kAllVariants) {
            if (variant.method == AoMethod::Horizon) continue; // its own tests: test_horizon_ao.cpp
            CAPTURE(projection.name, nameOf(variant.method), static_cast<int>(variant.march));
            checkWall(f, scene, variant.method, variant.march, {ObscuranceFalloff::None, true}, 256);
        }
    }
}

TEST_CASE("AO under a disc matches one minus its view factor within the march and voxel bounds", "[ao]") {
    AoFixture f;
    constexpr double a = 1.0, h = 1.0;
    const Scene scene = test::withDisc(floorScene(20.0), a, h);
    // Seen from below the disc, so that the floor under it and its underside are both on
    // screen (the whole disc within the image: nothing is lost at the border).
    constexpr int W = 128, H = 128;
    const glm::vec3 eye(0.0f, 0.5f, 3.2f);
    f.render(scene, lookAt(eye, {0.0f, 0.45f, 0.0f}, W, H), W, H);
    constexpr double radius = 1.8; // > sqrt(h^2 + (a + 0.4)^2): covers the disc from rho < 0.4
    constexpr int rays = 64, steps = 256;
    constexpr double thickness = 0.01; // >= radius / steps: the first sample past the disc is inside
    // The ray march with view-space samples and with texture-space ones (the same points up
    // to rounding, so the same window) and Hi-Z (exactly the texture-space march's first
    // hit); voxels: grids of 128 and 512 columns and slices (the presets' low and high),
    // whose window narrows with the voxel side.
    struct Run {
        AoMethod method;
        int resolution;
        ScreenMarch march = ScreenMarch::View;
    };
    for (const Run run : {Run{AoMethod::RayMarch, 0}, Run{AoMethod::RayMarch, 0, ScreenMarch::Texture},
                          Run{AoMethod::RayMarch, 0, ScreenMarch::HiZ}, Run{AoMethod::Voxel, 128}, Run{AoMethod::Voxel, 512}}) {
        const AoMethod method = run.method;
        CAPTURE(nameOf(method), run.resolution, static_cast<int>(run.march));
        VoxelizerSettings voxels;
        voxels.resolution = std::max(run.resolution, 128);
        voxels.targets = voxels.resolution / 128;
        voxels.fitBox = false;
        voxels.boxMin = glm::vec3(-2.0f, -0.5f, -2.0f);
        voxels.boxMax = glm::vec3(2.0f, 1.5f, 2.0f);
        const double voxelSide = 4.0 / voxels.resolution, lift = std::sqrt(3.0) * voxelSide; // the largest side
        AmbientOcclusionSettings s;
        s.method = method;
        s.march = run.march;
        s.radius = static_cast<float>(radius);
        s.rays = rays;
        s.steps = steps;
        s.thickness = static_cast<float>(thickness);
        const Image ao = f.run(scene, s, voxels);
        double meanError = 0.0, meanWindow = 0.0, meanExactError = 0.0;
        int checked = 0;
        for (int y = 0; y < H; ++y)
            for (int x = 0; x < W; ++x) {
                if (!f.geometry(x, y)) continue;
                const glm::dvec3 p = f.world(x, y);
                const double rho = std::hypot(p.x, p.z);
                if (std::abs(p.y) > 1e-3 || rho > 0.4) continue;
                double lo, hi;
                if (method == AoMethod::RayMarch) {
                    // The first sample past the disc is at most radius / steps further along
                    // the ray, so at most that much (<= thickness) above it; seen from the eye
                    // it projects up to delta = D * (radius / steps) / (h - eye.y) (D: the eye's
                    // horizontal distance, < 4.2 m) off its crossing point: crossings within
                    // delta of the rim can be missed. A ray passing outside the rim counts as
                    // hidden while it stays within `thickness` above the disc's plane and
                    // projects onto the disc, at most D * thickness / (h - eye.y) beyond the rim.
                    const double delta = 4.2 * (radius / steps) / (h - eye.y);
                    lo = discAo(rho, a + 4.2 * thickness / (h - eye.y), h);
                    hi = discAo(rho, a - delta, h);
                } else {
                    // Rays start a voxel diagonal up (and a little more: the depth's error and
                    // a 2^-8 margin, well within the side below); the disc's voxels reach a
                    // voxel side down and a side diagonal out (conservative surface voxelization).
                    lo = discAo(rho, a + std::sqrt(2.0) * voxelSide, h - lift - voxelSide);
                    hi = discAo(rho, a, h - lift);
                }
                const double sigma = std::sqrt(std::max({lo * (1.0 - lo), hi * (1.0 - hi), 1.0 / rays}) / rays);
                const double value = ao.at(x, y, 0), tolerance = 5.0 * sigma + std::ldexp(1.0, -12); // half float
                CAPTURE(x, y, rho, value, lo, hi, discAo(rho, a, h));
                CHECK(value >= lo - tolerance);
                CHECK(value <= hi + tolerance);
                meanError += value - 0.5 * (lo + hi);
                meanWindow += 0.5 * (hi - lo);
                meanExactError += value - discAo(rho, a, h);
                ++checked;
            }
        CHECK(checked > 100);
        // Independent per-pixel rotations: the mean stays within the mean bias window plus
        // 5 sigma / sqrt(pixels) (sigma <= 0.5 / sqrt(rays)), plus the half-float rounding.
        INFO("mean error " << meanError / checked << " from the window's centre (window +-" << meanWindow / checked
                           << "), " << meanExactError / checked << " from the closed form, over " << checked
                           << " pixels; on the axis h^2 / (h^2 + a^2) = " << discAo(0.0, a, h));
        CHECK(std::abs(meanError / checked) <=
              meanWindow / checked + 5.0 * 0.5 / std::sqrt(double(rays) * checked) + std::ldexp(1.0, -12));
    }
}

TEST_CASE("AO stays finite and within 0..1 for odd sizes and reversed-Z and orthographic views and the sky", "[ao][stability]") {
    AoFixture f;
    const assets::LoadedScene cornell = assets::builtinScene("cornell");
    struct View {
        int width, height;
        DepthMode mode;
        bool infiniteFar, orthographic;
        // 1400: the far plane cuts through the box at z = 200 of its 0..559 and through the
        // short block, so pixels of them lie at the far plane, next to clipped ones.
        float farPlane = 5000.0f;
    };
    for (const View& v : {View{1, 1, DepthMode::Standard, false, false}, View{37, 23, DepthMode::Standard, false, false},
                          View{23, 41, DepthMode::Reversed, false, false}, View{40, 30, DepthMode::Reversed, true, false},
                          View{33, 33, DepthMode::StandardZeroToOne, false, true},
                          View{30, 20, DepthMode::Reversed, false, true},
                          View{37, 29, DepthMode::Standard, false, false, 1400.0f},
                          View{29, 31, DepthMode::Reversed, false, false, 1400.0f},
                          View{31, 27, DepthMode::StandardZeroToOne, false, true, 1400.0f}}) {
        CAPTURE(v.width, v.height, static_cast<int>(v.mode), v.infiniteFar, v.orthographic, v.farPlane);
        const float aspect = float(v.width) / float(v.height);
        // Looking out of the box's open side too, so the sky (background) is in view.
        const LookAt look{{278, 273, -1200}, {278, 273, 0}, {0, 1, 0}};
        const Camera camera = v.orthographic ? Camera::orthographic(look, 400.0f, aspect, 10.0f, v.farPlane, v.mode)
                                             : Camera::perspective(look, glm::radians(40.0f), aspect, 10.0f,
                                                                   v.infiniteFar ? INFINITY : v.farPlane, v.mode);
        f.render(cornell.scene, camera, v.width, v.height, 2); // a back layer for depth peeling
        if (v.farPlane < 2000.0f) CHECK_FALSE(f.geometry(v.width / 2, v.height / 2)); // the tall block and the back wall are cut off
        if (!v.orthographic && v.width * v.height > 100 && v.farPlane > 2000.0f) {
            // The back wall faces the camera head-on: view normals of exactly (0, 0, 1), where
            // a tangent frame built by crossing with the z axis degenerates.
            const Image normals = readTexture(f.ctx, f.view.normal);
            int headOn = 0;
            for (int y = 0; y < v.height; ++y)
                for (int x = 0; x < v.width; ++x)
                    headOn += normals.at(x, y, 0) == 0.0f && normals.at(x, y, 1) == 0.0f && normals.at(x, y, 2) == 1.0f;
            CHECK(headOn > 0);
        }
        std::vector<AoVariant> variants(std::begin(kAllVariants), std::end(kAllVariants));
        for (const AoVariant peeled : {AoVariant{AoMethod::RayMarch, ScreenMarch::View, ScreenThickness::DepthPeeling},
                                       AoVariant{AoMethod::RayMarch, ScreenMarch::HiZ, ScreenThickness::DepthPeeling},
                                       AoVariant{AoMethod::Points, ScreenMarch::View, ScreenThickness::DepthPeeling},
                                       AoVariant{AoMethod::RayMarch, ScreenMarch::Texture, ScreenThickness::PeelingOrConstant},
                                       AoVariant{AoMethod::Points, ScreenMarch::View, ScreenThickness::PeelingOrConstant}})
            variants.push_back(peeled);
        for (const AoVariant variant : variants)
            for (AoResolution resolution : {AoResolution::Full, AoResolution::Quarter}) {
                CAPTURE(nameOf(variant.method), static_cast<int>(variant.march), static_cast<int>(variant.thickness),
                        static_cast<int>(resolution));
                AmbientOcclusionSettings s = test::settingsOf(variant);
                s.radius = 100.0f;
                s.rays = 8;
                s.resolution = resolution;
                s.blurRadius = 2;
                s.bentNormals = true;
                if (variant.method == AoMethod::Voxel) s.voxels = &f.voxelizer.voxelize(cornell.scene, {});
                const AmbientOcclusionView out = f.ao.run(f.view, s);
                const Image ao = readTexture(f.ctx, out.ao);
                REQUIRE(ao.width == v.width);
                REQUIRE(ao.height == v.height);
                std::size_t bad = 0, sky = 0, skyNotOne = 0;
                for (int y = 0; y < v.height; ++y)
                    for (int x = 0; x < v.width; ++x) {
                        const float a = ao.at(x, y, 0);
                        bad += !(a >= 0.0f && a <= 1.0f);
                        if (f.geometry(x, y)) continue;
                        ++sky;
                        skyNotOne += a != 1.0f; // background pixels are 1 (ambient_occlusion.hpp)
                    }
                CHECK(bad == 0);
                CHECK(skyNotOne == 0);
                if (v.width * v.height > 100) CHECK(sky > 0); // the open side shows the background
                if (s.bentNormals) {
                    const Image bent = readTexture(f.ctx, out.bentNormal);
                    for (float value : bent.pixels) CHECK(std::isfinite(value));
                }
            }
    }
}

TEST_CASE("AO with a radius past 1.8e19 units equals AO with a radius of 1e18", "[ao][stability]") {
    // The radius ranges over (0, inf). The Cornell box (559 units) from its camera: with any
    // radius far beyond it, a ray's samples lie so far out that they project to the pixel
    // its direction points at, behind the surface there by a share of the radius that does
    // not depend on the radius (the thickness is the radius), so AO must not change between
    // 1e18 and 1e30 but for pixel-edge ties. Past about 1.8e19 a sample's squared length
    // overflows float; the screen-space marches took the sample's length for their rounding
    // tolerance, so nothing was hidden and AO was 1 (screen_march.glsl). The horizon method
    // steps out of the image at such radii (open, 1 at both), the voxel traversal clips its
    // rays to the grid.
    AoFixture f;
    const assets::LoadedScene cornell = assets::builtinScene("cornell");
    constexpr int W = 48, H = 36;
    f.render(cornell.scene, assets::makeCamera(cornell.camera, W, H), W, H);
    for (const AoVariant variant : kAllVariants) {
        CAPTURE(nameOf(variant.method), static_cast<int>(variant.march));
        AmbientOcclusionSettings s = test::settingsOf(variant);
        s.rays = 16;
        s.radius = 1e18f;
        const Image control = f.run(cornell.scene, s);
        s.radius = 1e30f;
        const Image far = f.run(cornell.scene, s);
        std::size_t pixels = 0, differing = 0, bad = 0, occluded = 0;
        for (int y = 0; y < H; ++y)
            for (int x = 0; x < W; ++x) {
                const float a = far.at(x, y, 0);
                bad += !(a >= 0.0f && a <= 1.0f);
                if (!f.geometry(x, y)) continue;
                ++pixels;
                differing += a != control.at(x, y, 0);
                occluded += a < 1.0f;
            }
        INFO(differing << " of " << pixels << " pixels differ; " << occluded << " below 1");
        CHECK(bad == 0);
        CHECK(differing <= pixels / 100);
        // The rays that point into the image (from the floor, walls and blocks, seen at an
        // angle: a few percent of the cosine-weighted hemisphere) are hidden behind the back
        // wall, however far: a marching method must see some.
        if (variant.method == AoMethod::RayMarch || variant.method == AoMethod::Points) CHECK(occluded > pixels / 20);
    }
    CHECK(test::drainGlErrors().empty());
}

TEST_CASE("AO settings out of range are refused before any GL work", "[ao][bad-input]") {
    AoFixture f;
    const Scene scene = floorScene();
    f.render(scene, lookAt({0, 3, 6}, {0, 0, 0}, 16, 16), 16, 16);
    const auto before = test::liveGlObjects();
    for (auto change : std::vector<void (*)(AmbientOcclusionSettings&)>{
             [](AmbientOcclusionSettings& s) { s.radius = 0.0f; }, [](AmbientOcclusionSettings& s) { s.radius = NAN; },
             [](AmbientOcclusionSettings& s) { s.rays = 0; }, [](AmbientOcclusionSettings& s) { s.rays = 2000; },
             [](AmbientOcclusionSettings& s) { s.steps = 0; }, [](AmbientOcclusionSettings& s) { s.thickness = -1.0f; },
             [](AmbientOcclusionSettings& s) { s.blurRadius = 17; }, [](AmbientOcclusionSettings& s) { s.blurDepthSigma = 0.0f; },
             [](AmbientOcclusionSettings& s) { s.refineThreshold = -0.1f; },
             [](AmbientOcclusionSettings& s) { s.refineThreshold = NAN; },
             [](AmbientOcclusionSettings& s) { s.rayLanes = 0; }, [](AmbientOcclusionSettings& s) { s.rayLanes = 3; },
             [](AmbientOcclusionSettings& s) { s.rayLanes = 32; },
             [](AmbientOcclusionSettings& s) { s.method = AoMethod::Horizon, s.rays = 7; },
             [](AmbientOcclusionSettings& s) { s.method = AoMethod::Horizon, s.cosineWeighted = false; },
             [](AmbientOcclusionSettings& s) { s.method = AoMethod::Horizon, s.falloff = ObscuranceFalloff::Linear; },
             [](AmbientOcclusionSettings& s) { s.method = AoMethod::Voxel; },
             // Integers outside the enumerators (a division by a zero scale, an odd one the
             // upsampling cannot take, shader paths picked by accident).
             [](AmbientOcclusionSettings& s) { s.resolution = static_cast<AoResolution>(0); },
             [](AmbientOcclusionSettings& s) { s.resolution = static_cast<AoResolution>(3); },
             [](AmbientOcclusionSettings& s) { s.method = static_cast<AoMethod>(4); },
             [](AmbientOcclusionSettings& s) { s.falloff = static_cast<ObscuranceFalloff>(-1); },
             [](AmbientOcclusionSettings& s) { s.march = static_cast<ScreenMarch>(3); },
             [](AmbientOcclusionSettings& s) { s.thicknessMode = static_cast<ScreenThickness>(3); },
             [](AmbientOcclusionSettings& s) { s.thicknessMode = static_cast<ScreenThickness>(-1); },
             // Valid, but the fixture's G-buffer has one depth layer.
             [](AmbientOcclusionSettings& s) { s.thicknessMode = ScreenThickness::PeelingOrConstant; }}) {
        AmbientOcclusionSettings s;
        change(s);
        CHECK_THROWS_AS(f.ao.run(f.view, s), Error);
    }
    GBufferView noDepth = f.view;
    noDepth.depth = f.view.normal;
    CHECK_THROWS_AS(f.ao.run(noDepth, {}), Error);
    CHECK(test::drainGlErrors().empty());
    CHECK(test::liveGlObjects() == before);
}
