#include "obscura/metrics.hpp"

#include "obscura/error.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

namespace obscura::metrics {
namespace {

void check(const Image& t, const Image& r, const Options& o) {
    const auto consistent = [](const Image& i) {
        return i.width > 0 && i.height > 0 && i.channels > 0 &&
               i.pixels.size() == static_cast<std::size_t>(i.width) * i.height * i.channels;
    };
    if (!consistent(t) || !consistent(r))
        throw Error(ErrorCode::InvalidArgument, "metrics: an image is empty or its pixel count is inconsistent");
    if (t.width != r.width || t.height != r.height || t.channels != r.channels)
        throw Error(ErrorCode::InvalidArgument, "metrics: images differ in size or channels (" + std::to_string(t.width) +
                                                    "x" + std::to_string(t.height) + "x" + std::to_string(t.channels) +
                                                    " vs " + std::to_string(r.width) + "x" + std::to_string(r.height) +
                                                    "x" + std::to_string(r.channels) + ")");
    if (o.mask && (o.mask->width != t.width || o.mask->height != t.height || o.mask->channels != 1 || !consistent(*o.mask)))
        throw Error(ErrorCode::InvalidArgument, "metrics: the mask must be a 1-channel image of the same size");
    if (!(o.relativeEpsilon > 0.0) || std::isinf(o.relativeEpsilon) || !(o.outlierFraction >= 0.0 && o.outlierFraction < 0.5) ||
        !(o.peak > 0.0) || std::isinf(o.peak))
        throw Error(ErrorCode::InvalidArgument,
                    "metrics: relativeEpsilon and peak must be finite and > 0, outlierFraction in [0, 0.5)");
}

bool counted(const Options& o, std::size_t pixel) { return !o.mask || o.mask->pixels[pixel] > 0.0f; }

double tonemap(double x) { return x > 0.0 ? x / (1.0 + x) : 0.0; }

} // namespace

Report compare(const Image& t, const Image& r, const Options& o) {
    check(t, r, o);
    Report rep;
    const std::size_t pixels = static_cast<std::size_t>(t.width) * t.height;
    const auto c = static_cast<std::size_t>(t.channels);
    double sq = 0.0, abs = 0.0;
    std::vector<double> relative; // per-pixel mean relative squared error, for outlier rejection
    relative.reserve(pixels);
    for (std::size_t p = 0; p < pixels; ++p) {
        if (!counted(o, p)) continue;
        double rel = 0.0;
        std::size_t finite = 0;
        for (std::size_t k = 0; k < c; ++k) {
            const double tv = t.pixels[p * c + k], rv = r.pixels[p * c + k];
            if (std::isnan(tv)) {
                ++rep.nanCount;
                continue;
            }
            if (std::isinf(tv)) {
                ++rep.infCount;
                continue;
            }
            const double d = tv - rv;
            sq += d * d;
            abs += std::abs(d);
            rep.maxAbs = std::max(rep.maxAbs, std::abs(d));
            rel += d * d / (rv * rv + o.relativeEpsilon);
            ++finite;
        }
        rep.values += finite;
        if (finite) relative.push_back(rel / static_cast<double>(finite));
    }
    if (rep.values == 0) {
        rep.psnr = std::numeric_limits<double>::infinity();
        return rep;
    }
    const auto n = static_cast<double>(rep.values);
    rep.mse = sq / n;
    rep.rmse = std::sqrt(rep.mse);
    rep.meanAbs = abs / n;
    rep.psnr = rep.mse > 0.0 ? 10.0 * std::log10(o.peak * o.peak / rep.mse) : std::numeric_limits<double>::infinity();
    // relMSE over pixels, dropping the largest `outlierFraction` of them.
    std::sort(relative.begin(), relative.end());
    const auto keep =
        relative.size() - static_cast<std::size_t>(std::floor(o.outlierFraction * static_cast<double>(relative.size())));
    double relSum = 0.0;
    for (std::size_t i = 0; i < keep; ++i) relSum += relative[i];
    rep.relMse = keep ? relSum / static_cast<double>(keep) : 0.0;
    rep.ssim = ssim(t, r, o);
    return rep;
}

double mse(const Image& t, const Image& r, const Options& o) { return compare(t, r, o).mse; }
double rmse(const Image& t, const Image& r, const Options& o) { return compare(t, r, o).rmse; }
double relMse(const Image& t, const Image& r, const Options& o) { return compare(t, r, o).relMse; }
double psnr(const Image& t, const Image& r, const Options& o) { return compare(t, r, o).psnr; }

double ssim(const Image& t, const Image& r, const Options& o) {
    check(t, r, o);
    constexpr int radius = 5;
    constexpr double sigma = 1.5, c1 = 0.01 * 0.01, c2 = 0.03 * 0.03;
    double kernel[2 * radius + 1];
    for (int i = -radius; i <= radius; ++i) kernel[i + radius] = std::exp(-(i * i) / (2.0 * sigma * sigma));
    const int w = t.width, h = t.height, c = t.channels;
    for (float v : r.pixels)
        if (v < 0.0f) return std::numeric_limits<double>::quiet_NaN();
    const auto usable = [&](int x, int y, int k) {
        const std::size_t p = static_cast<std::size_t>(y) * w + x;
        return counted(o, p) && std::isfinite(t.pixels[p * c + k]);
    };
    double total = 0.0;
    std::size_t count = 0;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            for (int k = 0; k < c; ++k) {
                if (!usable(x, y, k)) continue;
                double sw = 0, mx = 0, my = 0, sxx = 0, syy = 0, sxy = 0;
                for (int dy = -radius; dy <= radius; ++dy)
                    for (int dx = -radius; dx <= radius; ++dx) {
                        const int xx = x + dx, yy = y + dy;
                        if (xx < 0 || yy < 0 || xx >= w || yy >= h || !usable(xx, yy, k)) continue;
                        const double wt = kernel[dx + radius] * kernel[dy + radius];
                        const std::size_t i = (static_cast<std::size_t>(yy) * w + xx) * c + k;
                        const double a = tonemap(t.pixels[i]), b = tonemap(r.pixels[i]);
                        sw += wt;
                        mx += wt * a;
                        my += wt * b;
                        sxx += wt * a * a;
                        syy += wt * b * b;
                        sxy += wt * a * b;
                    }
                mx /= sw;
                my /= sw;
                const double vx = std::max(0.0, sxx / sw - mx * mx), vy = std::max(0.0, syy / sw - my * my);
                const double cxy = sxy / sw - mx * my;
                total += ((2 * mx * my + c1) * (2 * cxy + c2)) / ((mx * mx + my * my + c1) * (vx + vy + c2));
                ++count;
            }
    return count ? total / static_cast<double>(count) : 1.0;
}

double halvesNoiseMse(const Image& a, const Image& b, const Options& o) { return compare(a, b, o).mse / 4.0; }

} // namespace obscura::metrics
