// Brings host normals to the G-buffer contract (view space, unit, facing the camera), or
// reconstructs them from depth when the host has none (FROM_DEPTH).
//! variant: FROM_DEPTH
//! variant: UNSIGNED_ENCODING WORLD_SPACE
//! variant: FROM_DEPTH COUNT_NEAR_PLANE
#include "../common/depth.glsl"
#include "../common/math.glsl"
#include "gbuffer_bindings.h"

layout(local_size_x = GBUFFER_WORKGROUP_SIZE, local_size_y = GBUFFER_WORKGROUP_SIZE) in;
layout(binding = GBUFFER_DEPTH_TEXTURE_UNIT) uniform sampler2D depthTexture;
#ifndef FROM_DEPTH
layout(binding = GBUFFER_NORMAL_TEXTURE_UNIT) uniform sampler2D normalTexture;
#endif
layout(binding = GBUFFER_OUTPUT_IMAGE_UNIT, rgba16f) writeonly uniform image2D normals;
#ifdef COUNT_NEAR_PLANE
// Diagnostic::DepthOnNearPlane: pixels whose depth is exactly the near plane's, where no
// rendered surface lies (a background cleared for the other depth convention).
layout(std430, binding = GBUFFER_NEAR_PLANE_SSBO) buffer NearPlane {
    uint nearPlanePixels;
};
#endif

// A reconstructed point and how far it may lie from the surface point it samples: the depth's
// step (depthReconstructionError) and float rounding.
struct SurfacePoint {
    vec3 p;
    float error;
};

SurfacePoint surfacePoint(vec3 p, float depth) {
    return SurfacePoint(p, depthReconstructionError(p, depth) + kPositionRounding * positionRoundingScale(p));
}

// A neighbour's point, or `valid = false` outside the image or on background.
SurfacePoint neighbour(ivec2 pixel, out bool valid) {
    valid = all(greaterThanEqual(pixel, ivec2(0))) && all(lessThan(pixel, frameSize()));
    if (!valid) return SurfacePoint(vec3(0.0), 0.0);
    const float d = texelFetch(depthTexture, pixel, 0).r;
    valid = !isBackground(d);
    return valid ? surfacePoint(viewPositionFromDepth(pixelCenterUv(pixel), d), d) : SurfacePoint(vec3(0.0), 0.0);
}

// Of the two one-sided differences along an axis, the one with the smaller depth step
// stays on the same surface at silhouettes. `error` bounds its distance from the difference
// of the surface points: the sum of the two points' errors. Zero where neither neighbour is
// geometry.
SurfacePoint tangent(ivec2 pixel, ivec2 axis, SurfacePoint p) {
    bool okPlus, okMinus;
    const SurfacePoint plus = neighbour(pixel + axis, okPlus);
    const SurfacePoint minus = neighbour(pixel - axis, okMinus);
    if (okPlus && (!okMinus || abs(plus.p.z - p.p.z) <= abs(p.p.z - minus.p.z)))
        return SurfacePoint(plus.p - p.p, plus.error + p.error);
    if (okMinus) return SurfacePoint(p.p - minus.p, p.error + minus.error);
    return SurfacePoint(vec3(0.0), 0.0);
}

#ifdef FROM_DEPTH
// A bound on the distance between the unit normal of a x b, turned toward the camera c, and
// that of the plane the points lie on. The surface points' differences lie within a.error and
// b.error of a and b, so their cross product lies within m = ea |b| + eb |a| + ea eb (plus
// the cross product's rounding) of a x b, and its direction within the angle whose sine is
// r = m / |a x b|: apart by the chord 2 sin(angle / 2) = r sqrt(2 / (1 + sqrt(1 - r^2)))
// (sqrt and division only: GLSL leaves asin's precision open). Turning toward the camera
// keeps that where the normal's dot product with c exceeds the chord (the dot products of
// the two unit normals differ by at most it); elsewhere, and where m >= |a x b|, 2: any
// direction.
float crossNormalError(SurfacePoint a, SurfacePoint b, vec3 c) {
    const vec3 n = cross(a.p, b.p);
    const float lenA = length(a.p), lenB = length(b.p), lenN = length(n);
    const float m = a.error * lenB + b.error * lenA + a.error * b.error + kPositionRounding * lenA * lenB;
    if (!(m < lenN)) return 2.0;
    const float r = m / lenN;
    const float chord = r * sqrt(2.0 / (1.0 + sqrt(1.0 - r * r)));
    return abs(dot(n, c)) > chord * lenN ? chord : 2.0;
}
#endif

#ifndef FROM_DEPTH
// How far a bent normal faces the camera: dot(n, toCamera) after bending, enough that the
// half-float store (2^-10 relative) keeps it on the camera's side.
const float kBentFacing = 1.0 / 64.0;

// HostGBuffer::normalDeviation as a chord, 2 sin(deviation / 2): how far the host's normals
// may lie from their faces'.
layout(location = GBUFFER_LOC_NORMAL_DEVIATION) uniform float shadingDeviation;

// A host normal (unit) that faces away from the camera is one of two things: a back face's,
// drawn two-sided, which turned around is its surface's; or a smooth shading normal past a
// silhouette (interpolated from vertices whose faces turn away), which turned around would
// point into the surface (AO about 0 there). The depth tells them apart: the plane through
// the pixel and its neighbours, turned toward the camera, lies on the shading normal's side.
// Such a normal is bent just enough to face the camera: its component along the view ray
// past the view plane removed, so that it keeps its direction in the view plane.
vec3 hostNormalFacingCamera(vec3 n, vec3 toCamera, ivec2 pixel, SurfacePoint centre, out float bentBy) {
    bentBy = 0.0;
    const float facing = dot(n, toCamera);
    if (facing >= 0.0) return n;
    vec3 g = cross(tangent(pixel, ivec2(1, 0), centre).p, tangent(pixel, ivec2(0, 1), centre).p);
    if (dot(g, toCamera) < 0.0) g = -g;
    if (dot(n, g) < 0.0) return -n; // a back face's
    // |n - (facing - k) toCamera|^2 = 1 - facing^2 + k^2 >= k^2: never zero.
    const vec3 bent = normalize(n - (facing - kBentFacing) * toCamera);
    bentBy = length(bent - n);
    return bent;
}
#endif

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(pixel, frameSize()))) return;
    float depth = texelFetch(depthTexture, pixel, 0).r;
    if (isBackground(depth)) {
        imageStore(normals, pixel, vec4(0.0));
        return;
    }
#ifdef COUNT_NEAR_PLANE
    if (depth == (frame.reversedZ != 0 ? 1.0 : 0.0)) atomicAdd(nearPlanePixels, 1u);
#endif
    vec3 p = viewPositionFromDepth(pixelCenterUv(pixel), depth);
    vec3 toCamera = viewDirectionTo(p);
    float errorScale = 1.0; // alpha: this pixel's normal error in units of the view's
#ifdef FROM_DEPTH
    const SurfacePoint centre = surfacePoint(p, depth);
    const SurfacePoint along = tangent(pixel, ivec2(1, 0), centre), across = tangent(pixel, ivec2(0, 1), centre);
    vec3 n = cross(along.p, across.p);
    // The view's normalError (kHalfNormalError) covers the half-float store; the reconstruction
    // adds its own bound, scaled up by 2^-9 so that the store's rounding of alpha (2^-10
    // relative, toward zero on llvmpipe) cannot lower it.
    errorScale = (1.0 + crossNormalError(along, across, toCamera) / storedNormalError()) * (1.0 + 1.0 / 512.0);
#else
    vec3 n = texelFetch(normalTexture, pixel, 0).xyz;
#ifdef UNSIGNED_ENCODING
    n = n * 2.0 - 1.0;
#endif
#ifdef WORLD_SPACE
    n = mat3(frame.view) * n;
#endif
#endif
    n = safeNormalize(n, toCamera);
#ifdef FROM_DEPTH
    if (dot(n, toCamera) < 0.0) n = -n;
#else
    float bentBy;
    n = hostNormalFacingCamera(n, toCamera, pixel, surfacePoint(p, depth), bentBy);
    // The screen tests trust a stored normal to within its bound, so that a surface does not
    // occlude itself: shading normals and bent ones add how far they may lie from the face
    // (scaled up by 2^-9, as FROM_DEPTH's bound, so that the half-float store cannot lower it).
    const float offFace = shadingDeviation + bentBy;
    if (offFace > 0.0) errorScale = (1.0 + offFace / storedNormalError()) * (1.0 + 1.0 / 512.0);
#endif
    imageStore(normals, pixel, vec4(n, errorScale));
}
