#include "shadows/light_frusta.hpp"

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <array>
#include <cmath>

namespace obscura::detail {
namespace {

std::array<glm::dvec3, 8> boundsCorners(const Bounds& b) {
    std::array<glm::dvec3, 8> c;
    for (int i = 0; i < 8; ++i)
        c[static_cast<std::size_t>(i)] = glm::dvec3(i & 1 ? b.max.x : b.min.x, i & 2 ? b.max.y : b.min.y, i & 4 ? b.max.z : b.min.z);
    return c;
}

// The view-space point of an image corner (ndc x, y in {-1, 1}) at view distance d.
glm::dvec3 viewCorner(const Camera& camera, ProjectionKind kind, double x, double y, double d) {
    const glm::dmat4 p(camera.projection);
    if (kind == ProjectionKind::Perspective) // at z = -1: x_ndc = p00 x - p20 (row 3 is (0, 0, -1, 0))
        return glm::dvec3((x + p[2][0]) / p[0][0] * d, (y + p[2][1]) / p[1][1] * d, -d);
    return glm::dvec3((x - p[3][0]) / p[0][0], (y - p[3][1]) / p[1][1], -d);
}

// Rounds r up to a multiple of 2^-8 of its power of two: the same sphere size from frame to
// frame although its corners are recomputed with different rounding.
double quantizeUp(double r) {
    const double q = std::ldexp(1.0, static_cast<int>(std::floor(std::log2(r))) - 8);
    return std::ceil(r / q) * q;
}

} // namespace

std::vector<double> cascadeSplits(double nearest, double farthest, int count, double lambda) {
    std::vector<double> ends;
    for (int i = 1; i <= count; ++i) {
        const double f = static_cast<double>(i) / count;
        const double logarithmic = nearest * std::pow(farthest / nearest, f);
        const double uniform = nearest + (farthest - nearest) * f;
        ends.push_back(i == count ? farthest : lambda * logarithmic + (1.0 - lambda) * uniform);
    }
    return ends;
}

DistanceRange visibleDistances(const Camera& camera, const Bounds& bounds) {
    const ProjectionInfo info = analyzeProjection(camera);
    const glm::dmat4 view(camera.view);
    double lo = INFINITY, hi = -INFINITY;
    for (const glm::dvec3& c : boundsCorners(bounds)) {
        const double d = -(view * glm::dvec4(c, 1.0)).z;
        lo = std::min(lo, d);
        hi = std::max(hi, d);
    }
    DistanceRange r{std::max(lo, double(info.nearPlane)), std::min(hi, double(info.farPlane))};
    if (!(r.farthest > r.nearest)) r = {info.nearPlane, 2.0 * info.nearPlane};
    return r;
}

glm::dvec3 lightUp(const glm::dvec3& direction) {
    return std::abs(direction.y) < 0.9 ? glm::dvec3(0.0, 1.0, 0.0) : glm::dvec3(1.0, 0.0, 0.0);
}

LightCamera directionalCascade(const glm::dvec3& direction, const Camera& camera, double from, double to,
                               const Bounds& bounds, int resolution) {
    const ProjectionKind kind = analyzeProjection(camera).kind;
    const glm::dmat4 viewToWorld = glm::inverse(glm::dmat4(camera.view));
    std::array<glm::dvec3, 8> corners;
    glm::dvec3 centre(0.0);
    for (int i = 0; i < 8; ++i) {
        const glm::dvec3 v = viewCorner(camera, kind, i & 1 ? 1.0 : -1.0, i & 2 ? 1.0 : -1.0, i & 4 ? to : from);
        corners[static_cast<std::size_t>(i)] = glm::dvec3(viewToWorld * glm::dvec4(v, 1.0));
        centre += corners[static_cast<std::size_t>(i)] / 8.0;
    }
    double radius = 0.0;
    for (const glm::dvec3& c : corners) radius = std::max(radius, glm::length(c - centre));
    // Snapping moves the centre by up to half a texel: one texel of margin on every side.
    radius = quantizeUp(std::max(radius, 1e-30)) * (1.0 + 2.0 / resolution);
    // Light space: x = right, y = up, z = along the light.
    const glm::dvec3 forward = glm::normalize(direction);
    const glm::dvec3 right = glm::normalize(glm::cross(forward, lightUp(forward)));
    const glm::dvec3 up = glm::cross(right, forward);
    const double texel = 2.0 * radius / resolution;
    const double x = std::round(glm::dot(centre, right) / texel) * texel;
    const double y = std::round(glm::dot(centre, up) / texel) * texel;
    double zmin = INFINITY, zmax = -INFINITY;
    for (const glm::dvec3& c : boundsCorners(bounds)) {
        zmin = std::min(zmin, glm::dot(c, forward));
        zmax = std::max(zmax, glm::dot(c, forward));
    }
    const double margin = 0.01 * std::max(zmax - zmin, radius);
    const glm::dvec3 eye = right * x + up * y + forward * (zmin - margin);
    LightCamera out;
    out.camera = Camera::orthographic({glm::vec3(eye), glm::vec3(eye + forward), glm::vec3(up)}, static_cast<float>(radius), 1.0f,
                                      static_cast<float>(0.5 * margin), static_cast<float>(zmax - zmin + 2.0 * margin),
                                      DepthMode::Reversed);
    out.texelSize = texel;
    return out;
}

LightCamera spotCamera(const Light& light, const Bounds& bounds, int resolution) {
    const glm::dvec3 eye(light.position), forward = glm::normalize(glm::dvec3(light.direction));
    double farthest = 0.0;
    for (const glm::dvec3& c : boundsCorners(bounds)) farthest = std::max(farthest, glm::dot(c - eye, forward));
    // A scene wholly behind the spot: an empty map of any extent.
    const double far = farthest > 0.0 ? 1.01 * farthest : 1.0;
    const double fovy = 2.0 * light.outerAngle;
    LightCamera out;
    out.camera = Camera::perspective({glm::vec3(eye), glm::vec3(eye + forward), glm::vec3(lightUp(forward))},
                                     static_cast<float>(fovy), 1.0f, static_cast<float>(far * 1e-4), static_cast<float>(far),
                                     DepthMode::Reversed);
    out.texelSize = 2.0 * std::tan(0.5 * fovy) / resolution;
    return out;
}

namespace {

// Far plane of a point light's maps: just past the bounds' farthest corner.
double pointFarPlane(const glm::dvec3& eye, const Bounds& bounds) {
    double farthest = 0.0;
    for (const glm::dvec3& c : boundsCorners(bounds)) farthest = std::max(farthest, glm::length(c - eye));
    return farthest > 0.0 ? 1.01 * farthest : 1.0;
}

} // namespace

LightCamera pointFace(const Light& light, int face, const Bounds& bounds, int resolution, int marginTexels) {
    const glm::dvec3 eye(light.position);
    glm::dvec3 axis(0.0);
    axis[face / 2] = face % 2 == 0 ? 1.0 : -1.0;
    const double far = pointFarPlane(eye, bounds);
    // tan(half fov) = 1 + the margin in texels of the 90-degree face (2 / resolution each).
    const double halfTan = 1.0 / (1.0 - 2.0 * marginTexels / resolution);
    const double fovy = 2.0 * std::atan(halfTan);
    LightCamera out;
    out.camera = Camera::perspective({glm::vec3(eye), glm::vec3(eye + axis), glm::vec3(lightUp(axis))},
                                     static_cast<float>(fovy), 1.0f, static_cast<float>(far * 1e-4), static_cast<float>(far),
                                     DepthMode::Reversed);
    out.texelSize = 2.0 * halfTan / resolution;
    return out;
}

namespace {

// The paraboloid map at `eye` along unit `axis`, its x along `side` made orthogonal to it.
ParaboloidMap paraboloidMap(const glm::dvec3& eye, const glm::dvec3& axis, const glm::dvec3& side, const Bounds& bounds,
                            int resolution) {
    // Rows: the map's x, y and axis z in world space (orthonormal; y = z cross x).
    const glm::dvec3 z = axis, x = glm::normalize(side - z * glm::dot(side, z)), y = glm::cross(z, x);
    glm::dmat4 rotation(1.0);
    for (int c = 0; c < 3; ++c) {
        rotation[c][0] = x[c];
        rotation[c][1] = y[c];
        rotation[c][2] = z[c];
    }
    ParaboloidMap out;
    out.worldToMap = rotation * glm::translate(glm::dmat4(1.0), -eye);
    // The cube's depth range, as a function of distance rather than of depth along an axis:
    // reversed-Z d = (near / L) (far - L) / (far - near), 1 at the near plane, 0 at the far.
    const double far = pointFarPlane(eye, bounds), near = far * 1e-4;
    out.depthMapping = glm::dvec4(near / (far - near), near * far / (far - near), near, far);
    out.texelSize = 2.0 / resolution;
    return out;
}

} // namespace

ParaboloidMap paraboloidHemisphere(const Light& light, int hemisphere, const Bounds& bounds, int resolution) {
    return paraboloidMap(glm::dvec3(light.position), {0.0, hemisphere == 0 ? -1.0 : 1.0, 0.0}, {1.0, 0.0, 0.0}, bounds,
                         resolution);
}

ParaboloidMap rectParaboloid(const Light& light, const Bounds& bounds, int resolution) {
    // validateScene guarantees a direction of length > 0 and a tangent not parallel to it.
    const glm::dvec3 axis = glm::normalize(glm::dvec3(light.direction));
    return paraboloidMap(glm::dvec3(light.position), axis, glm::dvec3(light.tangent), bounds, resolution);
}

} // namespace obscura::detail
