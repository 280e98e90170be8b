#pragma once
// Camera: the view and projection the G-buffer was (or will be) rendered with.
//
// Conventions: view space is right-handed and the camera looks down -z (OpenGL). World
// units are whatever the scene uses (the Cornell box is in millimetres). Depth is stored as
// 32-bit float. Reversed-Z (near → 1, far → 0, optionally an infinite far plane) needs
// ClipDepth::ZeroToOne; Obscura sets glClipControl accordingly when it rasterizes.
// Texture row 0 is the bottom of the view (glClipControl's GL_LOWER_LEFT origin, the GL
// default): a host that renders with GL_UPPER_LEFT stores its rows the other way round, and
// its buffers reconstruct mirrored in y unless the projection given here mirrors y too: its
// own with row 1 negated (projection[c][1] = -projection[c][1] for every column c), which is
// what GL_UPPER_LEFT does to y_ndc. Results then come out in the host's rows (tested for
// every AO and indirect-light method at full and half resolution: test_ao_host.cpp,
// test_indirect_light.cpp).
#include "obscura/export.hpp"

#include <glm/glm.hpp>

namespace obscura {

//! The glClipControl depth mode the projection was made for: window depth is
//! d = 0.5 * z_ndc + 0.5 (NegativeOneToOne, the GL default) or d = z_ndc (ZeroToOne).
enum class ClipDepth { NegativeOneToOne, ZeroToOne };

enum class ProjectionKind { Perspective, Orthographic };

enum class DepthMode {
    Standard,          //!< near → 0, far → 1, ClipDepth::NegativeOneToOne (GL default)
    StandardZeroToOne, //!< near → 0, far → 1, ClipDepth::ZeroToOne
    Reversed,          //!< near → 1, far → 0, ClipDepth::ZeroToOne; far may be infinite
};

struct LookAt {
    glm::vec3 eye{0.0f, 0.0f, 1.0f};    //!< world units
    glm::vec3 target{0.0f, 0.0f, 0.0f}; //!< world units, != eye
    glm::vec3 up{0.0f, 1.0f, 0.0f};     //!< not parallel to target - eye
};

struct Camera {
    glm::mat4 view{1.0f};       //!< world → view
    glm::mat4 projection{1.0f}; //!< view → clip; perspective rows 3 = (0,0,-1,0), orthographic (0,0,0,1)
    ClipDepth clipDepth = ClipDepth::NegativeOneToOne;

    //! fovy: vertical field of view, radians, (0, pi). aspect: width/height, (0, inf).
    //! near: world units, (0, far). far: world units, (near, inf]; inf only with Reversed.
    //! Throws Error{InvalidArgument} for values outside these ranges.
    OBSCURA_API static Camera perspective(const LookAt& lookAt, float fovy, float aspect, float nearPlane, float farPlane,
                              DepthMode mode = DepthMode::Standard);
    //! halfHeight: world units, (0, inf): half the height of the view volume. aspect:
    //! width/height, (0, inf). near: world units, (0, far). far: world units, (near, inf).
    //! Throws Error{InvalidArgument} for values outside these ranges.
    OBSCURA_API static Camera orthographic(const LookAt& lookAt, float halfHeight, float aspect, float nearPlane,
                               float farPlane, DepthMode mode = DepthMode::Standard);
};

//! What a projection matrix is, derived from the matrix (not trusted from the caller).
struct ProjectionInfo {
    ProjectionKind kind = ProjectionKind::Perspective;
    float nearPlane = 0.0f; //!< distance to the near plane, world units (> 0)
    float farPlane = 0.0f;  //!< distance to the far plane, world units (may be +inf)
    bool reversedZ = false; //!< near maps to depth 1
    float clearDepth = 1.0f; //!< depth of pixels nothing was drawn to: 1, or 0 with reversed-Z
};

//! Validates a camera (finite, invertible view; projection of a supported kind with
//! 0 < near < far) and describes it. Throws Error{InvalidArgument} saying what is wrong.
OBSCURA_API ProjectionInfo analyzeProjection(const Camera& camera);

//! Constants that turn a depth-buffer value back into a view-space position, computed in
//! double from the exact float matrix. With z_ndc = a*d + c,
//!   perspective:  z = zScale / ((d + zBiasHi) + zBiasLo),  x = -z * (ndc.x * xyScale.x + xyOffset.x)
//!   orthographic: z = zScale * d + zBiasHi,               x =       ndc.x * xyScale.x + xyOffset.x
//! Splitting the perspective bias into a float pair keeps d + bias exact where standard
//! depth cancels (d → 1 at the far plane), which a plain inverse-projection multiply loses:
//! with near/far 0.1/1000 the naive form has ~1e-3 relative error at the far end, this one
//! ~1e-7 (tests/gl/test_gbuffer.cpp).
struct DepthReconstruction {
    ProjectionKind kind = ProjectionKind::Perspective;
    float zScale = 0.0f;
    float zBiasHi = 0.0f;
    float zBiasLo = 0.0f;
    glm::vec2 xyScale{1.0f};
    glm::vec2 xyOffset{0.0f};
    float clearDepth = 1.0f; //!< background depth value, see ProjectionInfo
    //! The stored depth at which view z reaches -kMaxViewDistance, as a float (the clear
    //! depth where the far plane is nearer). Depths beyond it (below it with reversed-Z,
    //! above it otherwise) are background to every pass.
    float farthestDepth = 1.0f;
};

//! The farthest a surface may lie along the view axis, world units (2^56, about 7.2e16).
//! Beyond it a pixel is background: the passes square and add view positions and the
//! differences between them, which stay below FLT_MAX for |z| up to this and view rays up to
//! about 100 times as long as their z (a 179 degree field of view). Reached only with a far
//! plane past it: an infinite one (reversed-Z), where a host depth below near / 2^56 lies
//! beyond, or a huge finite one.
inline constexpr double kMaxViewDistance = 72057594037927936.0;

OBSCURA_API DepthReconstruction depthReconstruction(const Camera& camera);

//! Reference (double precision) inverse of the projection for a depth value d in [0,1]
//! at normalized device coordinates ndc in [-1,1]^2. For tests and CPU tools.
OBSCURA_API glm::dvec3 viewPositionFromDepth(const Camera& camera, glm::dvec2 ndc, double depth);

} // namespace obscura
