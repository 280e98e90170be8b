// Metrics against values computed by hand.
#include "obscura/error.hpp"
#include "obscura/metrics.hpp"

#include <catch2/catch.hpp>

#include <cmath>

using namespace obscura;

namespace {
Image image(int w, int h, int c, std::vector<float> v) {
    Image img;
    img.width = w;
    img.height = h;
    img.channels = c;
    img.pixels = std::move(v);
    return img;
}
} // namespace

TEST_CASE("MSE RMSE relMSE PSNR and absolute errors of a two-pixel image", "[unit][metrics]") {
    const Image test = image(2, 1, 1, {1.0f, 3.0f}), ref = image(2, 1, 1, {0.0f, 1.0f});
    const metrics::Report r = metrics::compare(test, ref);
    // errors 1 and 2
    CHECK(r.mse == Approx(2.5));
    CHECK(r.rmse == Approx(std::sqrt(2.5)));
    CHECK(r.meanAbs == Approx(1.5));
    CHECK(r.maxAbs == Approx(2.0));
    // 1 / (0 + 0.01) = 100 and 4 / (1 + 0.01) = 3.96040: mean 51.98020
    CHECK(r.relMse == Approx((100.0 + 4.0 / 1.01) / 2));
    // 10 log10(1 / 2.5) = -3.97940 dB
    CHECK(r.psnr == Approx(-3.9794000867));
    CHECK(r.values == 2);
    metrics::Options peak;
    peak.peak = 10.0;
    CHECK(metrics::psnr(test, ref, peak) == Approx(10.0 * std::log10(100.0 / 2.5)));
}

TEST_CASE("Masks select pixels and NaN or Inf values are counted not averaged", "[unit][metrics]") {
    const float nan = std::nanf(""), inf = INFINITY;
    const Image test = image(2, 2, 2, {1, 1, nan, 2, inf, 0, 5, 5});
    const Image ref = image(2, 2, 2, {0, 0, 0, 0, 0, 0, 0, 0});
    const metrics::Report all = metrics::compare(test, ref);
    CHECK(all.nanCount == 1);
    CHECK(all.infCount == 1);
    CHECK(all.values == 6);
    // squared errors of the finite values: 1, 1, 4, 0, 25, 25
    CHECK(all.mse == Approx(56.0 / 6.0));
    const Image mask = image(2, 2, 1, {1, 1, 0, 0});
    metrics::Options o;
    o.mask = &mask;
    const metrics::Report masked = metrics::compare(test, ref, o);
    CHECK(masked.values == 3);
    CHECK(masked.nanCount == 1);
    CHECK(masked.infCount == 0);
    CHECK(masked.mse == Approx(6.0 / 3.0));
}

TEST_CASE("relMSE drops the requested fraction of outlier pixels", "[unit][metrics]") {
    std::vector<float> t(1000, 1.1f), r(1000, 1.0f);
    t[17] = 1000.0f;
    const Image test = image(1000, 1, 1, t), ref = image(1000, 1, 1, r);
    metrics::Options o;
    const double plain = metrics::relMse(test, ref, o);
    o.outlierFraction = 0.001; // one pixel of 1000
    const double rejected = metrics::relMse(test, ref, o);
    // 0.01 / 1.01 per regular pixel
    CHECK(rejected == Approx(0.01 / 1.01).epsilon(1e-5));
    CHECK(plain == Approx((999 * 0.01 / 1.01 + 999.0 * 999.0 / 1.01) / 1000).epsilon(1e-5));
}

TEST_CASE("SSIM is 1 for equal images and follows the closed form for constant images", "[unit][metrics]") {
    const Image a = image(16, 16, 1, std::vector<float>(256, 1.0f));
    const Image b = image(16, 16, 1, std::vector<float>(256, 3.0f));
    CHECK(metrics::ssim(a, a) == Approx(1.0));
    // Constant images: zero variance, so SSIM = (2 mx my + C1) / (mx^2 + my^2 + C1) with
    // the tonemapped values mx = 1/2 and my = 3/4.
    CHECK(metrics::ssim(a, b) == Approx((2 * 0.5 * 0.75 + 1e-4) / (0.25 + 0.5625 + 1e-4)));
    // Two pixels, values chosen to tonemap to simple numbers (x/(1+x): 0 -> 0, 1 -> 1/2,
    // 1/3 -> 1/4, 3 -> 3/4). Each pixel's window holds both pixels, with Gaussian weights 1
    // (itself) and k = exp(-1/4.5) (the neighbour), normalized.
    {
        const Image t = image(2, 1, 1, {0.0f, 1.0f}), r = image(2, 1, 1, {1.0f / 3.0f, 3.0f});
        const double k = std::exp(-1.0 / 4.5), c1 = 1e-4, c2 = 9e-4;
        const double tx[2] = {0.0, 0.5}, ty[2] = {0.25, 0.75};
        double expected = 0;
        for (int p = 0; p < 2; ++p) {
            const double w[2] = {p == 0 ? 1 / (1 + k) : k / (1 + k), p == 0 ? k / (1 + k) : 1 / (1 + k)};
            const double mx = w[0] * tx[0] + w[1] * tx[1], my = w[0] * ty[0] + w[1] * ty[1];
            const double vx = w[0] * tx[0] * tx[0] + w[1] * tx[1] * tx[1] - mx * mx;
            const double vy = w[0] * ty[0] * ty[0] + w[1] * ty[1] * ty[1] - my * my;
            const double cxy = w[0] * tx[0] * ty[0] + w[1] * tx[1] * ty[1] - mx * my;
            expected += ((2 * mx * my + c1) * (2 * cxy + c2)) / ((mx * mx + my * my + c1) * (vx + vy + c2)) / 2;
        }
        CHECK(metrics::ssim(t, r) == Approx(expected).epsilon(1e-6)); // 1/3 is stored as a float
    }
    // Signed references (positions, normals) have no SSIM.
    CHECK(std::isnan(metrics::ssim(a, image(16, 16, 1, std::vector<float>(256, -1.0f)))));
    // A checkerboard against its inverse: anti-correlated, SSIM well below 0.
    std::vector<float> c(256), d(256);
    for (int i = 0; i < 256; ++i) {
        c[static_cast<std::size_t>(i)] = ((i / 16 + i % 16) % 2) ? 1.0f : 0.0f;
        d[static_cast<std::size_t>(i)] = 1.0f - c[static_cast<std::size_t>(i)];
    }
    CHECK(metrics::ssim(image(16, 16, 1, c), image(16, 16, 1, d)) < -0.5);
}

TEST_CASE("The halves' noise estimate is MSE(A B) over 4 and bad inputs are refused", "[unit][metrics]") {
    const Image a = image(2, 1, 1, {1.0f, 2.0f}), b = image(2, 1, 1, {3.0f, 2.0f});
    CHECK(metrics::halvesNoiseMse(a, b) == Approx(4.0 / 2 / 4));
    CHECK_THROWS_AS(metrics::mse(a, image(1, 1, 1, {0.0f})), Error);
    const Image wrongMask = image(2, 1, 2, {1, 1, 1, 1});
    metrics::Options o;
    o.mask = &wrongMask;
    CHECK_THROWS_AS(metrics::mse(a, b, o), Error);
    metrics::Options infinite; // documented (0, inf): an infinite epsilon or peak made every error 0 or Inf
    infinite.relativeEpsilon = INFINITY;
    CHECK_THROWS_WITH(metrics::relMse(a, b, infinite), Catch::Contains("finite"));
    infinite = {};
    infinite.peak = INFINITY;
    CHECK_THROWS_WITH(metrics::psnr(a, b, infinite), Catch::Contains("finite"));
}
