// Participating media (obscura/media.hpp) against the double-precision quadrature of the
// single-scattering integral (media_airlight.hpp) pixel by pixel: each method within the
// error its documentation states, the optical depth exact to half-float rounding, apply()'s
// composition, and no NaN or Inf on stiff and extreme media.
#include "ao_fixture.hpp"
#include "gl_fixture.hpp"
#include "media_airlight.hpp"
#include "scene_builders.hpp"

#include "obscura/obscura.hpp"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <vector>

using namespace obscura;

namespace {

constexpr int W = 32, H = 24;

struct MediaFixture {
    test::GlFixture gl;
    Context ctx{gl.desc()};
    GBuffer gbuffer{ctx};
    Media media{ctx};
    GBufferView view;
    Image positions; // view space, alpha = geometry

    void render(const Scene& scene, const Camera& camera) {
        view = gbuffer.render(scene, camera, GBufferSettings{W, H, false, {}});
        positions = readTexture(ctx, gbuffer.positions(view));
    }

    // The world ray of pixel (x, y) (unit direction) and the distance to its surface (Inf on
    // background).
    test::ViewRay ray(int x, int y, double& end) const {
        const test::ViewRay v = test::pixelRay(view.camera, x, y, W, H); // view space, z = -1
        const glm::dmat4 toWorld = glm::inverse(glm::dmat4(view.camera.view));
        end = positions.at(x, y, 3) > 0.0f ? glm::length(test::texel3(positions, x, y)) : std::numeric_limits<double>::infinity();
        return {glm::dvec3(toWorld * glm::dvec4(v.origin, 1.0)), glm::normalize(glm::dmat3(toWorld) * v.direction)};
    }
};

// A fog box around the camera and a floor, lit by a point light inside it.
struct FogCase {
    Scene scene = test::floorScene(20.0);
    Camera camera = test::lookAt({0.3f, 1.4f, 4.0f}, {0, 0.4f, 0}, W, H);
    std::vector<Medium> media;
    std::vector<Light> lights;

    FogCase(glm::vec3 scattering, glm::vec3 absorption, PhaseFunction phase, float g) {
        Medium m;
        m.boxMin = {-3.0f, -0.5f, -3.0f};
        m.boxMax = {3.0f, 3.0f, 5.0f};
        m.scattering = scattering;
        m.absorption = absorption;
        m.phase = phase;
        m.anisotropy = g;
        media.push_back(m);
        Light l;
        l.position = {0.6f, 1.8f, 0.5f};
        l.intensity = 10.0f;
        l.color = {1.0f, 0.9f, 0.8f};
        lights.push_back(l);
    }
};

struct Errors {
    double worst = 0.0, sumAbs = 0.0, sumRef = 0.0, worstDepth = 0.0;
    std::size_t nonFinite = 0;
    double total() const { return sumRef > 0.0 ? sumAbs / sumRef : sumAbs; }
};

std::size_t countNonFinite(const Image& image) {
    return std::size_t(std::count_if(image.pixels.begin(), image.pixels.end(), [](float v) { return !std::isfinite(v); }));
}

// Half floats hold radiance to 2^-11 relative down to 2^-14, and in steps of 2^-24 below.
constexpr double kHalfSubnormalStep = 5.9604644775390625e-8;

// Per pixel and channel: |gpu - quadrature| / quadrature (worst), the image's summed absolute
// error over its summed radiance, and the optical depth's relative error.
// `stride`: every stride-th pixel along each axis (heterogeneous media's quadrature is slow).
Errors compare(MediaFixture& f, const FogCase& c, const MediaView& out, int stride = 1) {
    const Image s = readTexture(f.ctx, out.scattering), d = readTexture(f.ctx, out.opticalDepth);
    const bool constant = std::all_of(c.media.begin(), c.media.end(), [](const Medium& m) { return m.density == MediumDensity::Constant; });
    Errors e;
    for (int y = 0; y < H; y += stride)
        for (int x = 0; x < W; x += stride) {
            double end;
            const test::ViewRay r = f.ray(x, y, end);
            for (int ch = 0; ch < 3; ++ch) {
                const double gpu = s.at(x, y, ch), tau = d.at(x, y, ch);
                if (!std::isfinite(gpu) || !std::isfinite(tau)) ++e.nonFinite;
                const double ref = constant ? test::airlight(c.media, c.lights, r.origin, r.direction, end, ch)
                                            : test::airlight(c.media, c.lights, r.origin, r.direction, end, ch, 1e-5, 16);
                const double refTau = test::opticalDepth(c.media, r.origin, r.direction, end, ch);
                // Relative error, less the half float's absolute step for values in its subnormals.
                e.worst = std::max(e.worst, std::max(std::abs(gpu - ref) - kHalfSubnormalStep, 0.0) / std::max(ref, 1e-30));
                e.sumAbs += std::abs(gpu - ref);
                e.sumRef += ref;
                e.worstDepth = std::max(e.worstDepth, std::abs(tau - refTau) / std::max(refTau, 1e-30));
            }
        }
    return e;
}

MediaView run(MediaFixture& f, const FogCase& c, MediaSettings s) { return f.media.run(f.view, {c.media, c.lights}, s); }

} // namespace

TEST_CASE("Each media method matches the quadrature of the single-scattering integral", "[media]") {
    MediaFixture f;
    const FogCase c({0.2f, 0.3f, 0.4f}, {0.05f, 0.05f, 0.05f}, PhaseFunction::HenyeyGreenstein, 0.3f);
    f.render(c.scene, c.camera);
    MediaSettings s;

    SECTION("analytic, quadrature") {
        s.method = MediaMethod::Analytic;
        const Errors e = compare(f, c, run(f, c, s));
        INFO("worst " << e.worst << " total " << e.total() << " depth " << e.worstDepth);
        CHECK(e.nonFinite == 0);
        CHECK(e.worst < 0.01);
        CHECK(e.worstDepth < 2 * test::kHalfRelative);
    }
    SECTION("analytic, table") {
        s.method = MediaMethod::Analytic;
        s.integral = AnalyticIntegral::Table;
        FogCase iso({0.2f, 0.3f, 0.4f}, {0.05f, 0.05f, 0.05f}, PhaseFunction::Isotropic, 0.0f);
        const Errors e = compare(f, iso, run(f, iso, s));
        INFO("worst " << e.worst << " total " << e.total());
        CHECK(e.nonFinite == 0);
        CHECK(e.worst < 0.05);
    }
    SECTION("ray marching") {
        s.method = MediaMethod::RayMarch;
        s.jitter = false;
        s.steps = 256;
        const Errors e = compare(f, c, run(f, c, s));
        INFO("worst " << e.worst << " total " << e.total());
        CHECK(e.nonFinite == 0);
        CHECK(e.worst < 0.02);
    }
    SECTION("froxels") {
        // A froxel per pixel and 256 slices leave only the slices' steps: within 2 % (1.1 %
        // measured). Coarser grids blur the light's 1/d^2 peak across tiles (each froxel
        // lights its centre): the error falls as the tiles shrink.
        s.method = MediaMethod::Froxel;
        s.froxelTile = 1;
        s.steps = 256;
        const Errors fine = compare(f, c, run(f, c, s));
        s.steps = 64;
        s.froxelTile = 8;
        const Errors coarse = compare(f, c, run(f, c, s));
        s.froxelTile = 2;
        const Errors finer = compare(f, c, run(f, c, s));
        INFO("per-pixel grid: worst " << fine.worst << "; image error, 8 px tiles " << coarse.total() << ", 2 px "
                                      << finer.total());
        CHECK(fine.nonFinite + coarse.nonFinite + finer.nonFinite == 0);
        CHECK(fine.worst < 0.02);
        CHECK(finer.total() < 0.75 * coarse.total());
    }
}

TEST_CASE("Height fog and a density grid: ray marching and froxels match the quadrature", "[media]") {
    MediaFixture f;
    FogCase c({0.3f, 0.4f, 0.5f}, {0.05f, 0.05f, 0.05f}, PhaseFunction::HenyeyGreenstein, 0.3f);
    f.render(c.scene, c.camera);
    SECTION("height fog") {
        c.media[0].density = MediumDensity::Height;
        c.media[0].heightFalloff = 0.8f;
    }
    SECTION("noise grid") {
        c.media[0].density = MediumDensity::Grid;
        c.media[0].grid = std::make_shared<DensityGrid>(noiseDensityGrid({16, 12, 16}, 7));
    }
    MediaSettings s;
    s.jitter = false;
    s.steps = 256;
    s.densitySteps = 64;
    const Errors march = compare(f, c, run(f, c, s), 4);
    s.method = MediaMethod::Froxel;
    s.froxelTile = 1;
    const Errors froxel = compare(f, c, run(f, c, s), 4);
    // The constant case's bounds (2 % per pixel), the grid's density read with the sampler's
    // fixed-point weights and its optical depths from 64 midpoint steps.
    INFO("march: worst " << march.worst << ", depth " << march.worstDepth << "; froxel: worst " << froxel.worst);
    CHECK(march.nonFinite + froxel.nonFinite == 0);
    CHECK(march.worst < 0.02);
    CHECK(froxel.worst < 0.02);
    CHECK(march.worstDepth < 0.01);
    s.method = MediaMethod::Analytic;
    CHECK_THROWS_WITH(run(f, c, s), Catch::Contains("homogeneous"));
}

TEST_CASE("Marching at reduced resolution and blurred stays near the quadrature, fog on the sky kept", "[media][filters]") {
    MediaFixture f;
    FogCase c({0.2f, 0.3f, 0.4f}, {0.05f, 0.05f, 0.05f}, PhaseFunction::HenyeyGreenstein, 0.3f);
    // The light behind the camera: on a 32 x 24 image its 1/d^2 peak in view would span a
    // pixel or two, which no upsampling or blur can keep (each reduced pixel is 1/16 of the view).
    c.lights[0].position = {0.6f, 2.5f, 4.6f};
    f.render(c.scene, c.camera);
    MediaSettings s;
    s.steps = 256;
    s.jitter = false;
    const Errors full = compare(f, c, run(f, c, s));
    s.resolution = AoResolution::Half;
    const Errors half = compare(f, c, run(f, c, s));
    // The background (the sky above the floor) must get the fog its rays cross, not zero.
    const Image sky = readTexture(f.ctx, run(f, c, s).scattering);
    double skyWorst = 0.0;
    int skyPixels = 0;
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) {
            double end;
            const test::ViewRay r = f.ray(x, y, end);
            if (std::isfinite(end)) continue;
            ++skyPixels;
            const double ref = test::airlight(c.media, c.lights, r.origin, r.direction, end, 0);
            skyWorst = std::max(skyWorst, std::abs(sky.at(x, y, 0) - ref) / ref);
        }
    // Jitter at 16 steps is noise of about 1/16 per pixel; 2 taps each side at full resolution
    // average it over up to 5 x 5 pixels of similar depth.
    s.resolution = AoResolution::Full;
    s.jitter = true;
    s.steps = 16;
    const Errors noisy = compare(f, c, run(f, c, s));
    s.blurRadius = 2;
    const Errors blurred = compare(f, c, run(f, c, s));
    INFO("image error: full " << full.total() << ", half " << half.total() << "; sky pixels " << skyPixels << ", worst "
                              << skyWorst << "; 16 jittered steps " << noisy.total() << ", blurred " << blurred.total()
                              << "; optical depth at half resolution " << half.worstDepth);
    CHECK(full.nonFinite + half.nonFinite + noisy.nonFinite + blurred.nonFinite == 0);
    CHECK(full.worst < 0.02); // the march's bound (the first test case)
    CHECK(half.worstDepth < 2 * test::kHalfRelative); // per pixel at every resolution
    CHECK(skyPixels > 0);
    // Bilinear weights over 2-pixel spacing are exact for linear variation; the fog's path
    // through the box kinks where rays leave by its top instead of its back, and there the
    // interpolation errs by the kink's share of a pixel pair: within 5 % (0.7 % over the
    // image, 3.5 % at the worst sky pixel measured).
    CHECK(half.total() < 0.05);
    CHECK(skyWorst < 0.05);
    CHECK(blurred.total() < noisy.total());
}

namespace {

// The stiff and extreme cases of one medium: every method's outputs finite, and the analytic
// form (the one whose error does not depend on step counts) within 1 % of the quadrature.
void checkStiff(MediaFixture& f, const FogCase& c, double analyticBound) {
    for (MediaMethod method : {MediaMethod::RayMarch, MediaMethod::Analytic, MediaMethod::Froxel})
        for (int steps : {1, 1024}) {
            MediaSettings s;
            s.method = method;
            s.steps = method == MediaMethod::Froxel ? std::min(steps, 256) : steps;
            for (AnalyticIntegral integral : {AnalyticIntegral::Quadrature, AnalyticIntegral::Table}) {
                if (integral == AnalyticIntegral::Table && method != MediaMethod::Analytic) continue;
                s.integral = integral;
                CAPTURE(int(method), steps, int(integral));
                const MediaView out = run(f, c, s);
                const Image a = readTexture(f.ctx, out.scattering), d = readTexture(f.ctx, out.opticalDepth);
                CHECK(countNonFinite(a) == 0);
                CHECK(countNonFinite(d) == 0);
                if (method == MediaMethod::Analytic && integral == AnalyticIntegral::Quadrature && steps == 1024) {
                    const Errors e = compare(f, c, out);
                    INFO("analytic worst relative error " << e.worst);
                    CHECK(e.worst <= analyticBound);
                }
            }
        }
}

} // namespace

TEST_CASE("Media outputs stay finite and the analytic form exact on stiff and extreme media", "[media][stability]") {
    MediaFixture f;
    const FogCase base({0.2f, 0.3f, 0.4f}, {0.05f, 0.05f, 0.05f}, PhaseFunction::Isotropic, 0.0f);
    f.render(base.scene, base.camera);

    SECTION("extinction from 0 to 1e4 per unit") {
        // 1e-4 <= sigma_t: the half float's relative step 2^-11 plus the quadrature's 1024
        // intervals; at 1e-8 the radiance lies in the half float's subnormals (absolute step).
        for (float sigma : {0.0f, 1e-8f, 1e-4f, 1.0f, 1e2f, 1e4f}) {
            CAPTURE(sigma);
            checkStiff(f, FogCase(glm::vec3(0.8f * sigma), glm::vec3(0.2f * sigma), PhaseFunction::Isotropic, 0.0f), 0.01);
        }
    }
    SECTION("strongly forward and backward phase functions") {
        // obscura/media.hpp: the analytic quadrature's intervals sample the phase at their
        // middles; a peak narrower than an interval (width ~ 1 - |g| radians) is sampled
        // coarsely: 1 % up to |g| = 0.9, 10 % at |g| = 0.999 with 1024 intervals (8 % measured).
        for (PhaseFunction phase : {PhaseFunction::HenyeyGreenstein, PhaseFunction::Schlick})
            for (float g : {0.9f, -0.9f, 0.999f, -0.999f}) {
                CAPTURE(int(phase), g);
                checkStiff(f, FogCase({0.2f, 0.3f, 0.4f}, glm::vec3(0.05f), phase, g), std::abs(g) <= 0.9f ? 0.01 : 0.1);
            }
    }
    SECTION("the light on the view ray's line, behind the camera and past the surface") {
        // Pixel (16, 12)'s ray: the light 0.5 behind the eye (gamma = pi), then 2 units past the
        // floor point it sees (gamma -> 0, beyond the segment): finite limits, where Sun et al.'s
        // form divides by sin(gamma) = 0.
        double end;
        const test::ViewRay r = f.ray(16, 12, end);
        for (double at : {-0.5, end + 2.0}) {
            FogCase c = base;
            c.media[0].boxMin = {-30.0f, -30.0f, -30.0f};
            c.media[0].boxMax = {30.0f, 30.0f, 30.0f};
            c.lights[0].position = glm::vec3(r.origin + at * r.direction);
            CAPTURE(at);
            checkStiff(f, c, 0.01);
        }
    }
    SECTION("the light on the view ray inside the segment") {
        // A point light of radius 0 on the ray: the integral is infinite there. Finite
        // (saturated) outputs only.
        double end;
        const test::ViewRay r = f.ray(16, 12, end);
        FogCase c = base;
        c.lights[0].position = glm::vec3(r.origin + 0.5 * end * r.direction);
        checkStiff(f, c, std::numeric_limits<double>::infinity());
    }
}

TEST_CASE("Media results do not change when the scene is 1e4 times larger (distances to 1e5)", "[media][stability]") {
    // Every length times 1e4, sigma times 1e-4, the light's intensity times 1e8: optical
    // depths, I/d^2 and so the radiance are the same. The box then spans 6e4 units and the
    // background rays cross it to 8e4 from the camera.
    constexpr float k = 1e4f;
    const FogCase small({0.2f, 0.3f, 0.4f}, {0.05f, 0.05f, 0.05f}, PhaseFunction::HenyeyGreenstein, 0.3f);
    FogCase large = small;
    large.scene = test::floorScene(20.0 * k);
    large.camera = Camera::perspective({{0.3f * k, 1.4f * k, 4.0f * k}, {0.0f, 0.4f * k, 0.0f}, {0, 1, 0}}, glm::radians(50.0f),
                                       float(W) / float(H), 0.05f * k, 200.0f * k);
    large.media[0].boxMin *= k;
    large.media[0].boxMax *= k;
    large.media[0].scattering /= k;
    large.media[0].absorption /= k;
    large.lights[0].position *= k;
    large.lights[0].intensity *= k * k;
    for (MediaMethod method : {MediaMethod::RayMarch, MediaMethod::Analytic, MediaMethod::Froxel}) {
        CAPTURE(int(method));
        MediaSettings s;
        s.method = method;
        s.jitter = false;
        MediaFixture a, b;
        a.render(small.scene, small.camera);
        b.render(large.scene, large.camera);
        const Image sa = readTexture(a.ctx, run(a, small, s).scattering), sb = readTexture(b.ctx, run(b, large, s).scattering);
        double worst = 0.0;
        for (std::size_t i = 0; i < sa.pixels.size(); ++i) {
            CHECK(std::isfinite(sb.pixels[i]));
            const double e = std::abs(double(sb.pixels[i]) - sa.pixels[i]) / std::max(double(sa.pixels[i]), 1e-6);
            worst = std::max(worst, e);
        }
        // Float rounding of positions 1e4 times larger (2^-24 of 8e4 is 5e-3 units, 1e-7 of the
        // box) and the half-float outputs' 2^-11: within 1 %.
        INFO("worst relative difference " << worst);
        CHECK(worst < 0.01);
    }
}

TEST_CASE("Media::apply composes L exp(-tau) + L_s; no media means no pass and no memory", "[media]") {
    MediaFixture f;
    const FogCase c({0.2f, 0.3f, 0.4f}, {0.05f, 0.05f, 0.05f}, PhaseFunction::HenyeyGreenstein, 0.3f);
    f.render(c.scene, c.camera);
    const MediaView out = run(f, c, MediaSettings{});
    // Any frame of the view's size will do as the lit one: the scattering itself.
    const TextureView applied = f.media.apply(out, out.scattering);
    const Image s = readTexture(f.ctx, out.scattering), d = readTexture(f.ctx, out.opticalDepth), a = readTexture(f.ctx, applied);
    double worst = 0.0;
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x)
            for (int ch = 0; ch < 3; ++ch) {
                const double expected = s.at(x, y, ch) * std::exp(-double(d.at(x, y, ch))) + s.at(x, y, ch);
                worst = std::max(worst, std::abs(a.at(x, y, ch) - expected) / expected);
            }
    INFO("worst relative difference " << worst);
    CHECK(worst <= 2 * test::kHalfRelative); // the result's half-float rounding, and exp's float error

    const std::size_t held = f.media.memoryBytes();
    CHECK(held > 0);
    const MediaView none = f.media.run(f.view, {{}, c.lights}, MediaSettings{});
    CHECK_FALSE(none.scattering);
    CHECK(f.media.memoryBytes() == 0);
    CHECK(f.media.apply(none, out.scattering).name == out.scattering.name); // the frame as it was

    std::vector<Medium> many(9, c.media[0]);
    CHECK_THROWS_WITH(f.media.run(f.view, {many, c.lights}, MediaSettings{}), Catch::Contains("at most 8"));
    MediaSettings bad;
    bad.steps = 0;
    CHECK_THROWS_WITH(f.media.run(f.view, {c.media, c.lights}, bad), Catch::Contains("steps"));
}
