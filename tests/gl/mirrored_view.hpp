#pragma once
// What the GL_UPPER_LEFT tests share (camera.hpp: such a host passes its projection mirrored
// in y): the mirrored and the shifted projections, and a result's RMS differences from the
// unmirrored full-resolution one, whose noise baselines they are checked against.
#include "obscura/obscura.hpp"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstddef>

namespace obscura::test {

//! The projection with row `axis` negated, which mirrors x (0) or y (1): for y, what a
//! GL_UPPER_LEFT host passes.
inline Camera mirrored(Camera camera, int axis) {
    for (int column = 0; column < 4; ++column) camera.projection[column][axis] = -camera.projection[column][axis];
    return camera;
}

//! An off-centre projection whose image moves one pixel left: its pixel x sees what the
//! original's pixel x + 1 sees.
inline Camera shiftedOnePixel(Camera camera, int width) {
    camera.projection[2][0] += 2.0f / float(width);
    return camera;
}

//! RMS differences from `full` (the unmirrored camera at full resolution) over its geometry
//! pixels (`positions` alpha), over the first `channels` channels: the result mirrored in
//! `axis` (0: column W - 1 - x against column x, 1: row H - 1 - y against row y) at full
//! resolution, the shifted one (its x - 1 against x,
//! where it shows geometry), the mirrored and the unmirrored ones at half resolution.
struct MirroredDifferences {
    double mirrored = 0.0, shifted = 0.0, mirroredHalf = 0.0, half = 0.0;
    std::size_t pixels = 0, shiftedPixels = 0;
};

inline MirroredDifferences mirroredDifferences(const Image& positions, const Image& shiftedPositions, int channels,
                                               const Image& full, const Image& mirrored, const Image& shifted,
                                               const Image& half, const Image& mirroredHalf, int axis = 1) {
    const int w = full.width, h = full.height;
    const auto squared = [&](const Image& a, int ax, int ay, int x, int y) {
        double sum = 0.0;
        for (int c = 0; c < channels; ++c) {
            const double d = double(a.at(ax, ay, c)) - double(full.at(x, y, c));
            sum += d * d;
        }
        return sum;
    };
    double sums[4] = {0, 0, 0, 0};
    MirroredDifferences r;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            if (positions.at(x, y, 3) == 0.0f) continue;
            ++r.pixels;
            const int mx = axis == 0 ? w - 1 - x : x, my = axis == 1 ? h - 1 - y : y;
            sums[0] += squared(mirrored, mx, my, x, y);
            sums[2] += squared(mirroredHalf, mx, my, x, y);
            sums[3] += squared(half, x, y, x, y);
            if (x < 1 || shiftedPositions.at(x - 1, y, 3) == 0.0f) continue;
            ++r.shiftedPixels;
            sums[1] += squared(shifted, x - 1, y, x, y);
        }
    const auto rms = [](double sum, std::size_t n) { return std::sqrt(sum / double(std::max<std::size_t>(n, 1))); };
    r.mirrored = rms(sums[0], r.pixels);
    r.shifted = rms(sums[1], r.shiftedPixels);
    r.mirroredHalf = rms(sums[2], r.pixels);
    r.half = rms(sums[3], r.pixels);
    return r;
}

//! The mirrored results are estimates of what the unmirrored camera sees, as noisy as their
//! baselines: within 1.25 times the shifted result's RMS at full resolution (its pixels use
//! other noise texels, as the mirrored ones do), and at half resolution within 1.25 times the
//! unmirrored half-resolution result's RMS (mirrored, a reduced pixel stands for the other
//! row or column of its 2 x 2 block, so the result is another half-resolution estimate). Over the
//! 1000-2000 pixels of these tests an RMS of independent noise varies by about
//! 1 / sqrt(2 N), 2 %, a ratio of two by about 3 %; the blur correlates neighbouring pixels'
//! noise at half resolution, so fewer of them are independent there. Measured on llvmpipe:
//! 0.89-1.13 times the baselines; the horizon method walking unmirrored slices was 2.6-12.7
//! times them.
inline void checkMirroredLikeBaselines(const MirroredDifferences& d) {
    INFO(d.pixels << " pixels: RMS from full resolution: mirrored " << d.mirrored << ", shifted " << d.shifted << " ("
                  << d.shiftedPixels << " pixels); mirrored half " << d.mirroredHalf << ", half " << d.half);
    CHECK(d.shiftedPixels > d.pixels * 9 / 10);
    CHECK(d.mirrored <= 1.25 * d.shifted);
    CHECK(d.mirroredHalf <= 1.25 * d.half);
}

} // namespace obscura::test
