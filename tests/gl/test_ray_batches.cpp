// Integrators whose rays take many loop iterations: on llvmpipe, which stops every loop of an
// invocation after 65535 iterations in all, they run their rays in batches
// (src/core/ray_batches.hpp). Their estimates must not depend on how many iterations the rays
// take: many rays estimate what few rays do.
#include "cornell_frame.hpp"
#include "integrator_settings.hpp"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <functional>

using namespace obscura;

namespace {

// Same pixels, few and many rays: both estimate the pixel's integral without bias (rotated
// Hammersley sets, whatever their count), so their differences have mean 0 and, every pixel's
// rotation being its own, are independent: their mean over P pixels stays within 5 of its
// standard deviations, the differences' spread over sqrt(P) (the scene's own variation
// cancels in the differences). Channel 0; the half floats' rounding (2^-11 relative) added.
void checkSameMean(const Image& few, const Image& many, const Image& positions) {
    double sum = 0.0, sum2 = 0.0, magnitude = 0.0;
    int count = 0;
    for (int y = 0; y < few.height; ++y)
        for (int x = 0; x < few.width; ++x) {
            if (positions.at(x, y, 3) == 0.0f) continue;
            const double d = double(few.at(x, y, 0)) - double(many.at(x, y, 0));
            sum += d;
            sum2 += d * d;
            magnitude += std::abs(few.at(x, y, 0));
            ++count;
        }
    const double mean = sum / count, spread = std::sqrt(std::max(sum2 / count - mean * mean, 0.0));
    const double sigma = spread / std::sqrt(double(count));
    INFO("mean difference " << mean << ", sigma " << sigma << " over " << count << " pixels (mean value "
                            << magnitude / count << ")");
    CHECK(count > 500);
    CHECK(std::abs(mean) <= 5.0 * sigma + std::ldexp(magnitude / count, -11));
}

} // namespace

TEST_CASE("Estimates do not depend on how many loop iterations their rays take", "[ao][gi][batches]") {
    test::CornellFrame f(48, 48);
    const float radius = 96.07f; // a tenth of the box's diagonal
    // With many rays each case may take more loop iterations than llvmpipe's 65535, so there
    // it runs in batches: 1024 rays of 257 march steps; 512 slices of 2 x 257 horizon steps;
    // 1024 voxel rays of 5 radii through a grid of 512 (up to 770 voxels each). With the
    // batches turned off, the screen-space GI cases were off by 28 and 35 standard deviations
    // (their rays seldom hit early); the others moved by less than 5 (the capped loops still
    // take their first sample, or the rays end early). With every refined pixel's partial
    // sums in one slot, the half-resolution case was off by 9.
    struct Case {
        const char* name;
        std::function<Image(int rays)> run;
        int few, many;
    };
    VoxelizerSettings fine;
    fine.resolution = 512;
    fine.targets = 4;
    const VoxelGrid* grid = &f.voxelizer.voxelize(f.cornell.scene, fine);
    const auto ao = [&](AoMethod method, int steps, float reach) {
        return [&f, grid, method, steps, reach](int rays) {
            auto s = test::integratorSettings<AmbientOcclusionSettings>(reach, rays, steps);
            s.method = method;
            if (method == AoMethod::Voxel) s.voxels = grid;
            return readTexture(f.ctx, f.ao.run(f.view, s).ao);
        };
    };
    const auto gi = [&](GiMethod method, int steps, float reach, AoResolution resolution = AoResolution::Full) {
        return [&f, grid, method, steps, reach, resolution](int rays) {
            IndirectLightSettings s;
            s.method = method;
            s.rays = rays;
            s.steps = steps;
            s.radius = reach;
            s.resolution = resolution; // Half: blurred, upsampled and refined (the default threshold)
            s.blurRadius = resolution == AoResolution::Full ? 0 : 1;
            if (method == GiMethod::Hybrid) s.voxels = grid;
            return readTexture(f.ctx, f.gi.run(f.view, s).radiance);
        };
    };
    const Case cases[] = {
        {"ao raymarch", ao(AoMethod::RayMarch, 256, 0.4f * radius), 240, 1024},
        {"ao horizon", ao(AoMethod::Horizon, 256, radius), 240, 1024},
        {"ao voxel", ao(AoMethod::Voxel, 32, 5.0f * radius), 64, 1024},
        {"gi screen", gi(GiMethod::Screen, 256, 3.0f * radius), 240, 1024},
        // The refinement pass batches too, its partial sums kept per listed pixel. The blur
        // and the upsampling weigh by geometry only: linear in the values, still unbiased.
        {"gi screen half", gi(GiMethod::Screen, 256, 3.0f * radius, AoResolution::Half), 240, 1024},
        {"gi hybrid", gi(GiMethod::Hybrid, 32, 5.0f * radius), 64, 1024},
    };
    for (const Case& c : cases) {
        CAPTURE(c.name);
        checkSameMean(c.run(c.few), c.run(c.many), f.positions);
    }
}
