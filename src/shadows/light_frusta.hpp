#pragma once
// The cameras shadow maps are rendered with, fitted to the scene and the viewer (CPU, double
// precision; no GL).
#include "obscura/camera.hpp"
#include "obscura/scene.hpp"

#include <vector>

namespace obscura::detail {

//! Far ends of `count` slices of the view distance range [nearest, farthest]:
//! d_i = lambda * nearest * (farthest / nearest)^(i / count) + (1 - lambda) * (nearest +
//! (farthest - nearest) i / count), i = 1 .. count (the last is `farthest`).
std::vector<double> cascadeSplits(double nearest, double farthest, int count, double lambda);

//! The range of view distances (-z in view space) at which the camera can see the scene's
//! bounds: the bounds' corners' range clipped to the camera's near and far planes. When the
//! bounds lie wholly behind the camera or beyond its far plane, [near, near * 2].
struct DistanceRange {
    double nearest = 0.0, farthest = 0.0;
};
DistanceRange visibleDistances(const Camera& camera, const Bounds& bounds);

struct LightCamera {
    Camera camera;           //!< reversed-Z, clip control zero-to-one
    double texelSize = 0.0;  //!< world units (orthographic) or per unit distance (perspective)
};

//! The orthographic map of a directional light (unit `direction`, the way light travels)
//! over the camera's view distances [from, to]: the slice's bounding sphere, its centre
//! snapped to whole texels in light space, depth spanning the scene's bounds.
LightCamera directionalCascade(const glm::dvec3& direction, const Camera& camera, double from, double to,
                               const Bounds& bounds, int resolution);

//! The perspective map of a spot light over its outer cone, far plane at the bounds'
//! farthest corner.
LightCamera spotCamera(const Light& light, const Bounds& bounds, int resolution);

//! Face `face` (+x, -x, +y, -y, +z, -z) of a point light's cube: a perspective map along
//! that world axis, `marginTexels` texels wider than 90 degrees on every side, far plane at
//! the bounds' farthest corner.
LightCamera pointFace(const Light& light, int face, const Bounds& bounds, int resolution, int marginTexels);

//! A paraboloid map: one of a point light's two (hemisphere 0 looks down -y, 1 up +y), or a
//! rect light's one over the side it emits toward.
struct ParaboloidMap {
    glm::dmat4 worldToMap{1.0};   //!< rigid: the light at the origin, the map's axis +z
    glm::dvec4 depthMapping{0.0}; //!< a, b, near, far: window depth d = b / L - a at distance L
    double texelSize = 0.0;       //!< 2 / resolution: see ShadowMapInfo::texelSize
};
ParaboloidMap paraboloidHemisphere(const Light& light, int hemisphere, const Bounds& bounds, int resolution);
//! A rect light's map, from its centre: axis along Light::direction, x along its tangent.
ParaboloidMap rectParaboloid(const Light& light, const Bounds& bounds, int resolution);

//! A unit vector not parallel to `direction`: the up vector of a light's view.
glm::dvec3 lightUp(const glm::dvec3& direction);

} // namespace obscura::detail
