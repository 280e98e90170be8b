#include "obscura/camera.hpp"

#include "core/validate.hpp"
#include "obscura/error.hpp"

#include <cmath>
#include <limits>
#include <string>

namespace obscura {
namespace {

constexpr double kPi = 3.14159265358979323846;

glm::mat4 lookAtMatrix(const LookAt& l) {
    detail::requireFinite(l.eye, "LookAt::eye");
    detail::requireFinite(l.target, "LookAt::target");
    detail::requireFinite(l.up, "LookAt::up");
    const glm::dvec3 eye(l.eye), target(l.target), up(l.up);
    const glm::dvec3 forward = target - eye;
    const double fl = glm::length(forward);
    if (!(fl > 0.0)) throw Error(ErrorCode::InvalidArgument, "LookAt: eye and target coincide");
    const glm::dvec3 f = forward / fl;
    const glm::dvec3 side = glm::cross(f, up);
    const double sl = glm::length(side);
    // Relative test: the angle between up and the view direction, not a length in world units.
    if (!(sl > 1e-6 * glm::length(up)))
        throw Error(ErrorCode::InvalidArgument, "LookAt: up is zero or parallel to the view direction");
    const glm::dvec3 s = side / sl;
    const glm::dvec3 u = glm::cross(s, f);
    glm::dmat4 m(1.0);
    m[0][0] = s.x; m[1][0] = s.y; m[2][0] = s.z;
    m[0][1] = u.x; m[1][1] = u.y; m[2][1] = u.z;
    m[0][2] = -f.x; m[1][2] = -f.y; m[2][2] = -f.z;
    m[3][0] = -glm::dot(s, eye);
    m[3][1] = -glm::dot(u, eye);
    m[3][2] = glm::dot(f, eye);
    return glm::mat4(m);
}

void checkRange(float nearPlane, float farPlane, DepthMode mode) {
    detail::requireEnumerator(mode, {DepthMode::Standard, DepthMode::StandardZeroToOne, DepthMode::Reversed}, "camera DepthMode");
    if (!(nearPlane > 0.0f) || !std::isfinite(nearPlane))
        throw Error(ErrorCode::InvalidArgument, "camera near plane must be finite and > 0, got " + std::to_string(nearPlane));
    const bool infiniteFar = std::isinf(farPlane) && farPlane > 0.0f;
    if (infiniteFar && mode != DepthMode::Reversed)
        throw Error(ErrorCode::InvalidArgument, "an infinite far plane needs DepthMode::Reversed");
    if (!(farPlane > nearPlane))
        throw Error(ErrorCode::InvalidArgument, "camera far plane must be > near plane (" + std::to_string(nearPlane) +
                                                    "), got " + std::to_string(farPlane));
}

ClipDepth clipDepthOf(DepthMode mode) {
    return mode == DepthMode::Standard ? ClipDepth::NegativeOneToOne : ClipDepth::ZeroToOne;
}

// Depth rows of the projection, computed in double: z_clip = a*z + b, w_clip = -z (perspective).
void setDepthRow(glm::dmat4& p, double n, double f, DepthMode mode, bool perspective) {
    const bool infinite = std::isinf(f);
    if (perspective) {
        switch (mode) {
        case DepthMode::Standard: p[2][2] = -(f + n) / (f - n); p[3][2] = -2.0 * f * n / (f - n); break;
        case DepthMode::StandardZeroToOne: p[2][2] = -f / (f - n); p[3][2] = -f * n / (f - n); break;
        case DepthMode::Reversed:
            p[2][2] = infinite ? 0.0 : n / (f - n);
            p[3][2] = infinite ? n : f * n / (f - n);
            break;
        }
        p[2][3] = -1.0;
        p[3][3] = 0.0;
    } else {
        switch (mode) {
        case DepthMode::Standard: p[2][2] = -2.0 / (f - n); p[3][2] = -(f + n) / (f - n); break;
        case DepthMode::StandardZeroToOne: p[2][2] = -1.0 / (f - n); p[3][2] = -n / (f - n); break;
        case DepthMode::Reversed: p[2][2] = 1.0 / (f - n); p[3][2] = f / (f - n); break;
        }
    }
}

} // namespace

Camera Camera::perspective(const LookAt& lookAt, float fovy, float aspect, float nearPlane, float farPlane,
                           DepthMode mode) {
    if (!(fovy > 0.0f) || !(fovy < static_cast<float>(kPi)))
        throw Error(ErrorCode::InvalidArgument, "fovy must be in (0, pi) radians, got " + std::to_string(fovy));
    if (!(aspect > 0.0f) || !std::isfinite(aspect))
        throw Error(ErrorCode::InvalidArgument, "aspect must be finite and > 0, got " + std::to_string(aspect));
    checkRange(nearPlane, farPlane, mode);
    const double t = std::tan(0.5 * static_cast<double>(fovy));
    glm::dmat4 p(0.0);
    p[0][0] = 1.0 / (static_cast<double>(aspect) * t);
    p[1][1] = 1.0 / t;
    setDepthRow(p, nearPlane, farPlane, mode, true);
    return Camera{lookAtMatrix(lookAt), glm::mat4(p), clipDepthOf(mode)};
}

Camera Camera::orthographic(const LookAt& lookAt, float halfHeight, float aspect, float nearPlane, float farPlane,
                            DepthMode mode) {
    if (!(halfHeight > 0.0f) || !std::isfinite(halfHeight))
        throw Error(ErrorCode::InvalidArgument, "halfHeight must be finite and > 0, got " + std::to_string(halfHeight));
    if (!(aspect > 0.0f) || !std::isfinite(aspect))
        throw Error(ErrorCode::InvalidArgument, "aspect must be finite and > 0, got " + std::to_string(aspect));
    if (std::isinf(farPlane)) throw Error(ErrorCode::InvalidArgument, "an orthographic camera needs a finite far plane");
    checkRange(nearPlane, farPlane, mode);
    glm::dmat4 p(1.0);
    p[0][0] = 1.0 / (static_cast<double>(aspect) * halfHeight);
    p[1][1] = 1.0 / static_cast<double>(halfHeight);
    setDepthRow(p, nearPlane, farPlane, mode, false);
    return Camera{lookAtMatrix(lookAt), glm::mat4(p), clipDepthOf(mode)};
}

ProjectionInfo analyzeProjection(const Camera& camera) {
    detail::requireEnumerator(camera.clipDepth, {ClipDepth::NegativeOneToOne, ClipDepth::ZeroToOne}, "Camera::clipDepth");
    detail::requireFinite(camera.view, "Camera::view");
    detail::requireFinite(camera.projection, "Camera::projection");
    if (!(std::abs(glm::determinant(glm::dmat3(camera.view))) > 0.0))
        throw Error(ErrorCode::InvalidArgument, "Camera::view is singular");
    const glm::dmat4 p(camera.projection);
    ProjectionInfo info;
    const bool perspective = p[0][3] == 0.0 && p[1][3] == 0.0 && p[2][3] == -1.0 && p[3][3] == 0.0;
    const bool ortho = p[0][3] == 0.0 && p[1][3] == 0.0 && p[2][3] == 0.0 && p[3][3] == 1.0;
    if (!perspective && !ortho)
        throw Error(ErrorCode::InvalidArgument,
                    "Camera::projection is neither a right-handed perspective (last row 0,0,-1,0) nor an "
                    "orthographic projection (last row 0,0,0,1)");
    if (p[1][0] != 0.0 || p[0][1] != 0.0 || !(p[0][0] != 0.0) || !(p[1][1] != 0.0) || p[0][2] != 0.0 || p[1][2] != 0.0)
        throw Error(ErrorCode::InvalidArgument, "Camera::projection has shear or zero scale; only axis-aligned "
                                                "(possibly off-centre) projections are supported");
    info.kind = perspective ? ProjectionKind::Perspective : ProjectionKind::Orthographic;
    if (perspective ? (p[3][0] != 0.0 || p[3][1] != 0.0) : (p[2][0] != 0.0 || p[2][1] != 0.0))
        throw Error(ErrorCode::InvalidArgument, "Camera::projection is oblique; only axis-aligned projections are "
                                                "supported");
    const bool zeroToOne = camera.clipDepth == ClipDepth::ZeroToOne;
    // Invert d(z) at d = 0 and d = 1 to find the planes.
    const auto zAt = [&](double d) {
        const double zn = zeroToOne ? d : 2.0 * d - 1.0;
        if (perspective) return p[2][2] + zn == 0.0 ? -std::numeric_limits<double>::infinity() : -p[3][2] / (zn + p[2][2]);
        return (zn - p[3][2]) / p[2][2];
    };
    if (p[2][2] == 0.0 && !perspective) throw Error(ErrorCode::InvalidArgument, "Camera::projection maps all depths to one value");
    const double z0 = zAt(0.0), z1 = zAt(1.0);
    const double d0 = -z0, d1 = -z1; // distances of the planes where depth is 0 and 1
    info.reversedZ = d0 > d1;
    const double nearDist = info.reversedZ ? d1 : d0;
    const double farDist = info.reversedZ ? d0 : d1;
    if (!(nearDist > 0.0) || !(farDist > nearDist))
        throw Error(ErrorCode::InvalidArgument,
                    "Camera::projection does not map a range 0 < near < far in front of the camera to depth [0,1] "
                    "with this ClipDepth (check glClipControl depth mode and the matrix)");
    info.nearPlane = static_cast<float>(nearDist);
    info.farPlane = static_cast<float>(farDist);
    info.clearDepth = info.reversedZ ? 0.0f : 1.0f;
    return info;
}

DepthReconstruction depthReconstruction(const Camera& camera) {
    const ProjectionInfo info = analyzeProjection(camera);
    const glm::dmat4 p(camera.projection);
    const bool zeroToOne = camera.clipDepth == ClipDepth::ZeroToOne;
    // z_ndc = a*d + c with a = 1, c = 0 (ZeroToOne) or a = 2, c = -1.
    const double a = zeroToOne ? 1.0 : 2.0, c = zeroToOne ? 0.0 : -1.0;
    DepthReconstruction r;
    r.kind = info.kind;
    r.clearDepth = info.clearDepth;
    r.farthestDepth = info.clearDepth;
    if (info.farPlane > kMaxViewDistance) {
        // z(d) = -kMaxViewDistance solved for the depth, in double, as the rows below invert z.
        const double zn = info.kind == ProjectionKind::Perspective ? p[3][2] / kMaxViewDistance - p[2][2]
                                                                    : p[3][2] - kMaxViewDistance * p[2][2];
        r.farthestDepth = static_cast<float>((zn - c) / a);
    }
    if (info.kind == ProjectionKind::Perspective) {
        // -z*z_ndc = p22*z + p32  ⇒  z = -p32 / (z_ndc + p22) = (-p32/a) / (d + (c + p22)/a)
        r.zScale = static_cast<float>(-p[3][2] / a);
        const double bias = (c + p[2][2]) / a;
        r.zBiasHi = static_cast<float>(bias);
        r.zBiasLo = static_cast<float>(bias - static_cast<double>(r.zBiasHi));
        // x_ndc = (p00*x + p20*z) / -z  ⇒  x = -z * (x_ndc / p00 + p20 / p00)
        r.xyScale = glm::vec2(1.0 / p[0][0], 1.0 / p[1][1]);
        r.xyOffset = glm::vec2(p[2][0] / p[0][0], p[2][1] / p[1][1]);
    } else {
        // z_ndc = p22*z + p32  ⇒  z = (a*d + c - p32) / p22
        r.zScale = static_cast<float>(a / p[2][2]);
        r.zBiasHi = static_cast<float>((c - p[3][2]) / p[2][2]);
        r.zBiasLo = 0.0f;
        // x_ndc = p00*x + p30  ⇒  x = x_ndc / p00 - p30 / p00
        r.xyScale = glm::vec2(1.0 / p[0][0], 1.0 / p[1][1]);
        r.xyOffset = glm::vec2(-p[3][0] / p[0][0], -p[3][1] / p[1][1]);
    }
    return r;
}

glm::dvec3 viewPositionFromDepth(const Camera& camera, glm::dvec2 ndc, double depth) {
    const ProjectionInfo info = analyzeProjection(camera);
    const glm::dmat4 p(camera.projection);
    const double zn = camera.clipDepth == ClipDepth::ZeroToOne ? depth : 2.0 * depth - 1.0;
    if (info.kind == ProjectionKind::Perspective) {
        const double z = -p[3][2] / (zn + p[2][2]);
        return {-z * (ndc.x + p[2][0]) / p[0][0], -z * (ndc.y + p[2][1]) / p[1][1], z};
    }
    const double z = (zn - p[3][2]) / p[2][2];
    return {(ndc.x - p[3][0]) / p[0][0], (ndc.y - p[3][1]) / p[1][1], z};
}

} // namespace obscura
