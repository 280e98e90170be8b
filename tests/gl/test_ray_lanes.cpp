// Ray lanes (AmbientOcclusionSettings::rayLanes, IndirectLightSettings::rayLanes): several
// invocations share a pixel's rays and lane 0 adds their sums (shaders/common/ray_batch.glsl).
// The rays are the same as with one lane, only the order of the additions differs, so the
// results must agree to the rounding that order can change, derived below.
#include "cornell_frame.hpp"
#include "integrator_settings.hpp"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <functional>
#include <string>

using namespace obscura;

namespace {

constexpr double kFloatUnit = 0x1p-24; // float's unit roundoff
// Rounding to the nearest half float moves two values at most one spacing further apart: 2^-11
// in [0.5, 1) (AO), at most 2^-10 of the value anywhere (radiance).
constexpr double kHalfSpacingBelowOne = 0x1p-11, kHalfRelativeSpacing = 0x1p-10;

// Two sums of the same n terms added in different orders each lie within (n - 1) u sum|t|
// of the exact sum (u: float's unit roundoff), so within 2 (n - 1) u sum|t| of each other.
double reorderBound(int terms, double magnitude) { return 2.0 * (terms - 1) * kFloatUnit * magnitude; }

// Largest |a - b| over the geometry pixels and channels [0, channels), less `allowed(a, b)`:
// <= 0 passes.
double worstExcess(const Image& a, const Image& b, const Image& positions, int channels,
                   const std::function<double(double, double)>& allowed, int& compared) {
    double worst = -1e30;
    compared = 0;
    for (int y = 0; y < a.height; ++y)
        for (int x = 0; x < a.width; ++x) {
            if (positions.at(x, y, 3) == 0.0f) {
                for (int c = 0; c < channels; ++c) REQUIRE(a.at(x, y, c) == b.at(x, y, c)); // background: written alike
                continue;
            }
            ++compared;
            for (int c = 0; c < channels; ++c) {
                const double va = a.at(x, y, c), vb = b.at(x, y, c);
                REQUIRE(std::isfinite(va));
                worst = std::max(worst, std::abs(va - vb) - allowed(va, vb));
            }
        }
    return worst;
}

} // namespace

TEST_CASE("Ray lanes give each pixel the same rays: AO's counts exactly, other sums to their reordering's rounding",
          "[ao][gi][lanes]") {
    // Not multiples of the 8 x 8 workgroups, at full and half resolution: the last groups
    // hold pixels outside the image, whose lanes must still meet at the barrier.
    test::CornellFrame f(60, 44);
    const VoxelGrid* grid = &f.voxelizer.voxelize(f.cornell.scene, {});
    const float radius = 96.07f; // a tenth of the box's diagonal
    const auto aoRun = [&](AoMethod method, ObscuranceFalloff falloff, AoResolution resolution, int lanes) {
        auto s = test::integratorSettings<AmbientOcclusionSettings>(radius, 64, 16, resolution,
                                                                    resolution == AoResolution::Full ? 0 : 2);
        s.method = method;
        s.falloff = falloff;
        s.bentNormals = true;
        s.rayLanes = lanes;
        if (method == AoMethod::Voxel) s.voxels = grid;
        const AmbientOcclusionView v = f.ao.run(f.view, s);
        return std::make_pair(readTexture(f.ctx, v.ao), s.bentNormals ? readTexture(f.ctx, v.bentNormal) : Image{});
    };
    struct AoCase {
        const char* name;
        AoMethod method;
        ObscuranceFalloff falloff;
        AoResolution resolution;
        int lanes;
    };
    const AoCase aoCases[] = {
        {"raymarch", AoMethod::RayMarch, ObscuranceFalloff::None, AoResolution::Full, 16},
        {"points", AoMethod::Points, ObscuranceFalloff::None, AoResolution::Full, 4},
        {"voxel", AoMethod::Voxel, ObscuranceFalloff::None, AoResolution::Full, 2},
        {"raymarch half (refined pixels in lanes)", AoMethod::RayMarch, ObscuranceFalloff::None, AoResolution::Half, 16},
        {"points, linear obscurance", AoMethod::Points, ObscuranceFalloff::Linear, AoResolution::Full, 8},
        {"horizon", AoMethod::Horizon, ObscuranceFalloff::None, AoResolution::Full, 16},
        {"horizon half", AoMethod::Horizon, ObscuranceFalloff::None, AoResolution::Half, 8},
    };
    for (const AoCase& c : aoCases) {
        CAPTURE(c.name, c.lanes);
        const auto one = aoRun(c.method, c.falloff, c.resolution, 1);
        const auto many = aoRun(c.method, c.falloff, c.resolution, c.lanes);
        int compared = 0;
        // AO without a falloff: the sums are counts of 0s and 1s (the hidden rays, the rays),
        // exact in float in any order, so the value is bit for bit the same, filtered or not.
        // Otherwise (n terms): obscurance adds 1 - rho in [0, 1] over n rays, the horizon
        // open - visible arcs in [0, open] over n = rays / 2 slices, and its count, the open
        // arcs, is a float sum too: occluded / count within 2 reorderBound(n, count) / count
        // (the division's own rounding, a few u, is far below), then rounded to a half: one
        // spacing more. A filtered result is a weighted mean of such values (its weights
        // from the geometry alone, the same in both runs), rounded again at the blur's two
        // steps and the upsampling: a spacing each.
        const bool counts = c.method != AoMethod::Horizon && c.falloff == ObscuranceFalloff::None;
        const int n = c.method == AoMethod::Horizon ? 32 : 64;
        const int roundings = c.resolution == AoResolution::Full ? 1 : 4;
        const double aoBound = counts ? 0.0 : 4.0 * reorderBound(n, 1.0) + roundings * kHalfSpacingBelowOne;
        const double aoExcess = worstExcess(one.first, many.first, f.positions, 1, [&](double, double) { return aoBound; }, compared);
        INFO("AO: " << compared << " pixels, bound " << aoBound << ", worst excess " << aoExcess);
        CHECK(compared > 1000);
        CHECK(aoExcess <= 0.0);
        if (counts) CHECK(aoExcess == 0.0);
        if (one.second.width > 0) {
            // Bent normals: the sums of the open directions, in the same vec4 as the counts
            // checked exactly above, so every lane was added; their order's rounding is
            // amplified by normalizing a sum that may be short (open rays on either side).
            // That amplification has no bound without the sum's length, which is not written,
            // so 0.01 is a detector, not a precision claim: it catches a lane's directions lost
            // or doubled (leaving out the last lane failed it for raymarch, points and voxel),
            // and is 40 times the largest difference measured with llvmpipe (2.4e-4, a half
            // float's spacing at 0.25-0.5).
            const double bentExcess =
                worstExcess(one.second, many.second, f.positions, 3, [](double, double) { return 0.01; }, compared);
            INFO("bent normal worst excess over 0.01: " << bentExcess);
            CHECK(bentExcess <= 0.0);
        }
    }

    const auto giRun = [&](GiMethod method, AoResolution resolution, int rays, int lanes) {
        IndirectLightSettings s;
        s.method = method;
        s.rays = rays;
        s.steps = 16;
        s.radius = 3.0f * radius;
        s.resolution = resolution;
        s.blurRadius = resolution == AoResolution::Full ? 0 : 2;
        s.rayLanes = lanes;
        if (method == GiMethod::Hybrid) s.voxels = grid;
        return readTexture(f.ctx, f.gi.run(f.view, s).radiance);
    };
    struct GiCase {
        const char* name;
        GiMethod method;
        AoResolution resolution;
        int rays, lanes;
    };
    // 1024 hybrid rays through the default grid take more loop iterations than llvmpipe
    // allows an invocation (core/ray_batches.hpp): there they run in batches, of 2 x as many
    // rays with 2 lanes, so the batches' partial sums meet the lanes' too.
    const GiCase giCases[] = {
        {"screen", GiMethod::Screen, AoResolution::Full, 64, 16},
        {"screen half (refined pixels in lanes)", GiMethod::Screen, AoResolution::Half, 64, 16},
        {"hybrid", GiMethod::Hybrid, AoResolution::Full, 64, 4},
        {"hybrid, batched", GiMethod::Hybrid, AoResolution::Full, 1024, 2},
    };
    for (const GiCase& c : giCases) {
        CAPTURE(c.name, c.lanes);
        const Image one = giRun(c.method, c.resolution, c.rays, 1), many = giRun(c.method, c.resolution, c.rays, c.lanes);
        // Radiance sums of n non-negative terms: within reorderBound(n, sum) of each other,
        // relative to the value; then one half-float rounding per step (the albedo's product,
        // the same factor in both runs, before the last).
        const int roundings = c.resolution == AoResolution::Full ? 1 : 4;
        const double relative = reorderBound(c.rays, 1.0) + roundings * kHalfRelativeSpacing;
        int compared = 0;
        const double excess = worstExcess(one, many, f.positions, 3,
                                          [&](double a, double b) { return relative * std::max(std::abs(a), std::abs(b)); },
                                          compared);
        INFO(compared << " pixels, relative bound " << relative << ", worst excess " << excess);
        CHECK(compared > 1000);
        CHECK(excess <= 0.0);
    }
}
