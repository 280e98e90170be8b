#pragma once
// Per-pixel Monte Carlo estimators of the reference quantities.
#include "obscura/reference.hpp"
#include "reference/ray_scene_impl.hpp"
#include "reference/sampling.hpp"

#include <algorithm>
#include <functional>

namespace obscura::reference::detail {

//! Estimates a quantity at one point from `samples` samples; up to 4 channels; counts rays.
using Estimator = std::function<glm::dvec4(const ShadingPoint& point, int samples, PixelSampler& sampler,
                                           std::uint64_t& rays)>;

//! A spot light's smooth cone from cos(outer) to cos(inner), as the G-buffer shades it; a hard
//! edge when they coincide.
inline double spotCone(double c, double cosInner, double cosOuter) {
    const double width = cosInner - cosOuter;
    if (!(width > 0.0)) return c >= cosOuter ? 1.0 : 0.0;
    const double t = std::clamp((c - cosOuter) / width, 0.0, 1.0);
    return t * t * (3.0 - 2.0 * t);
}

//! Where secondary rays leave a shading point: off its surface by the larger of the point's
//! own uncertainty and the scene's float error (see offsetOrigin).
inline glm::vec3 surfaceOrigin(const RayScene::Impl& scene, const ShadingPoint& p) {
    return offsetOrigin(p.position, p.normal, std::max(p.uncertainty, scene.floatError));
}

//! Validates the quantity against the scene (throws Error{InvalidArgument}) and returns its
//! estimator. `surfaceOnly` tells whether background pixels are skipped.
Estimator makeEstimator(const RayScene::Impl& scene, const Quantity& quantity, bool& surfaceOnly);

// Families, in their own files.
Estimator occlusionEstimator(const RayScene::Impl& scene, const Quantity& quantity);
Estimator lightingEstimator(const RayScene::Impl& scene, const Quantity& quantity);
Estimator scatteringEstimator(const RayScene::Impl& scene, const SingleScattering& quantity);

} // namespace obscura::reference::detail
