// Rays from a surface point through the voxel grid. The surface's own voxels lie within a
// voxel diagonal of its plane, so a ray sees only other geometry while it stays more than that
// above the plane. The point is known within its depth's reconstruction error, and its normal n
// within a chord e (its pixel's bound, storedNormalError): the true normal m has
// dot(n, m) >= 1 - e^2/2, and a ray w rises off the true plane by at least dot(w, n) - e per
// unit length. The start is lifted along n until it lies, for every such m, above the own
// voxels with a margin of 2^-8 of that height; each ray is then traced only as far as it
// provably stays above them (all of it where dot(w, n) > e; else until half the margin is
// spent, the other half left to the rounding of the segment's end): in practice less than a
// voxel once the ray may sink faster than 1/300. A hit beyond may be the surface itself, as
// the screen tests' own-plane gate (screen_march.glsl) treats it: the ray counts as open (AO)
// or dark (GI).
// With e past 1 (60 degrees) no ray is trusted. This assumes the point lies within its
// depth's reconstruction error of the voxelized surface: a host whose depth is further off
// the scene it voxelizes (its own transforms' rounding, another level of detail) needs a
// coarser grid, or its rays may start inside the surface's own voxels.
#include "../common/depth.glsl"
#include "voxel_traversal.glsl"

struct VoxelSurfaceStart {
    vec3 start;        // the point lifted along n
    float clearance;   // how far above the own voxels the start lies, at least
    float normalError; // e
};

// diagonal: one voxel's diagonal in view units (the host's shape.z).
VoxelSurfaceStart voxelSurfaceStart(vec3 p, float depth, vec3 n, float normalError, float diagonal) {
    const float cosine = 1.0 - 0.5 * normalError * normalError;
    const float below = diagonal + depthReconstructionError(p, depth) + kPositionRounding * positionRoundingScale(p);
    const float lift = below * (1.0 + 1.0 / 256.0) / max(cosine, 0.5);
    const float clearance = cosine >= 0.5 ? lift * cosine - below : -1.0;
    return VoxelSurfaceStart(p + n * lift, clearance, normalError);
}

// The length along w, at most `reach`, over which the ray provably stays above the surface's
// own voxels (0: trace nothing).
float voxelClearLength(VoxelSurfaceStart s, vec3 n, vec3 w, float reach) {
    if (!(s.clearance > 0.0)) return 0.0;
    const float sink = s.normalError - dot(w, n); // the most the ray may fall per unit length
    return sink <= 0.0 ? reach : min(reach, 0.5 * s.clearance / sink);
}

// The end of a ray from `start` along w, `reach` long (view space), in voxel coordinates. A
// radius so large that the end lies past the traversals' coordinate limit (voxelAcceptedPoint)
// would make them refuse the whole ray as a miss; past the grid nothing is hit, so the ray is
// shortened to where its end is at most half the limit from the start, and `reach` with it
// (a hit's distance is its t times reach). Other rays keep their end and reach unchanged.
vec3 voxelTraceableEnd(mat4 viewToVoxel, vec3 start, vec3 w, inout float reach) {
    const vec3 end = (viewToVoxel * vec4(start + w * reach, 1.0)).xyz;
    if (voxelAcceptedPoint(end)) return end;
    const vec3 perUnit = abs((viewToVoxel * vec4(w, 0.0)).xyz); // voxels per view unit along w
    reach = min(reach, 0.5 * kVoxelMaxCoordinate / max(max(perUnit.x, perUnit.y), max(perUnit.z, 1e-30)));
    return (viewToVoxel * vec4(start + w * reach, 1.0)).xyz;
}
