#pragma once
// Error metrics between a technique's image and its reference, over the same pixels.
//
// All metrics compare `test` against `reference` channel by channel over the pixels where
// `mask` (1 channel, optional) is > 0, and skip values that are NaN or infinite in `test`
// (they are counted instead). Images must have the same size and channel count.
#include "obscura/export.hpp"
#include "obscura/texture.hpp"

#include <cstddef>

namespace obscura::metrics {

struct Options {
    const Image* mask = nullptr;  //!< 1 channel, same size; pixels with mask > 0 count. Null: all pixels.
    double relativeEpsilon = 0.01; //!< relMSE denominator term, (0, inf)
    //! relMSE only: this fraction of the pixels with the largest relative error is dropped
    //! (0.001 = 0.1 %), [0, 0.5).
    double outlierFraction = 0.0;
    double peak = 1.0;             //!< PSNR peak value, (0, inf)
};

struct Report {
    double mse = 0.0;      //!< mean of (t - r)^2
    double rmse = 0.0;     //!< sqrt(mse)
    double relMse = 0.0;   //!< mean of (t - r)^2 / (r^2 + epsilon)
    double psnr = 0.0;     //!< 10 log10(peak^2 / mse), dB; +inf when mse = 0
    //! SSIM (Wang et al. 2004) of the tonemapped images, in [-1, 1]; NaN when the reference
    //! has negative values (signed data such as positions and normals: the tonemap is for
    //! radiance-like quantities).
    double ssim = 1.0;
    double meanAbs = 0.0;  //!< mean of |t - r|
    double maxAbs = 0.0;   //!< max of |t - r|
    std::size_t nanCount = 0; //!< NaN values in test (over the compared pixels and channels)
    std::size_t infCount = 0; //!< infinite values in test
    std::size_t values = 0;   //!< finite values compared (pixels x channels)
};

//! Throws Error{InvalidArgument} for mismatched sizes or channel counts, a bad mask or options.
OBSCURA_API Report compare(const Image& test, const Image& reference, const Options& options = {});

OBSCURA_API double mse(const Image& test, const Image& reference, const Options& options = {});
OBSCURA_API double rmse(const Image& test, const Image& reference, const Options& options = {});
OBSCURA_API double relMse(const Image& test, const Image& reference, const Options& options = {});
OBSCURA_API double psnr(const Image& test, const Image& reference, const Options& options = {});
//! Gaussian window 11x11, sigma 1.5, C1 = (0.01)^2, C2 = (0.03)^2 on images tonemapped per
//! channel by x / (1 + x) (negative values clamped to 0), so the dynamic range is 1. The
//! SSIM map is averaged over channels and masked pixels; windows are cut at the borders and
//! the mask (weights renormalized). NaN when the reference has negative values.
OBSCURA_API double ssim(const Image& test, const Image& reference, const Options& options = {});

//! MSE(A, B) / 4: the estimated MSE of the mean of two independent estimates A and B.
OBSCURA_API double halvesNoiseMse(const Image& halfA, const Image& halfB, const Options& options = {});

} // namespace obscura::metrics
