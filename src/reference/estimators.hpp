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
