// Surface voxelization, step 1: each triangle is projected along its dominant axis (so no
// triangle is seen edge-on) and replaced by its 2D bounding box grown by one pixel, so every
// voxel column it touches gets a fragment (conservative rasterization without hardware
// support; the fragment shader then tests each candidate voxel exactly).
#include "voxel_params.glsl"

layout(triangles) in;
layout(triangle_strip, max_vertices = 4) out;

in dvec3 vVoxel[];
// The triangle in projected (u, v, w) voxel coordinates relative to the integer corner
// gOrigin: float keeps 24 bits of the triangle's own extent, not of its place in the grid.
flat out vec3 gA, gB, gC;
flat out ivec3 gOrigin;
flat out int gAxis;   // the projection axis (w): 0 = x, 1 = y, 2 = z
flat out float gGrow; // how far the voxel boxes are grown against float rounding, voxels

// (u, v, w) with w along the axis; u, v the image plane.
dvec3 permute(dvec3 p, int axis) { return axis == 0 ? p.yzx : (axis == 1 ? p.zxy : p); }

bool finite(dvec3 p) { return !any(isnan(p)) && !any(isinf(p)); }

void main() {
    const dvec3 a = vVoxel[0], b = vVoxel[1], c = vVoxel[2];
    if (!finite(a) || !finite(b) || !finite(c)) return;
    const dvec3 n = abs(cross(b - a, c - a));
    int axis = (n.x >= n.y && n.x >= n.z) ? 0 : (n.y >= n.z ? 1 : 2);
    if (max(n.x, max(n.y, n.z)) == 0.0) {
        // Zero area: a segment or a point, voxelized as such (the separating axis test
        // handles it). Project along the axis of least extent, so it is not seen end-on.
        const dvec3 extent = max(a, max(b, c)) - min(a, min(b, c));
        axis = (extent.x <= extent.y && extent.x <= extent.z) ? 0 : (extent.y <= extent.z ? 1 : 2);
    }
    const dvec3 pa = permute(a, axis), pb = permute(b, axis), pc = permute(c, axis);
    const dvec3 origin = floor(min(pa, min(pb, pc)));
    gA = vec3(pa - origin);
    gB = vec3(pb - origin);
    gC = vec3(pc - origin);
    gOrigin = ivec3(origin);
    gAxis = axis;
    // The separating-axis test's float error grows with the triangle's extent E (its
    // coordinates here are in [0, E]): a few ulp of E, plus a floor for tiny triangles.
    const float extent = max(max(max(gA.x, gA.y), max(gA.z, gB.x)), max(max(gB.y, gB.z), max(gC.x, max(gC.y, gC.z))));
    gGrow = 1e-5 + 8.0 * extent / 16777216.0;
    const vec2 lo = vec2(origin.xy) + floor(min(gA.xy, min(gB.xy, gC.xy))) - 1.0;
    const vec2 hi = vec2(origin.xy) + ceil(max(gA.xy, max(gB.xy, gC.xy))) + 1.0;
    const float size = float(voxel.counts.z);
    const vec2 corners[4] = vec2[4](vec2(lo.x, lo.y), vec2(hi.x, lo.y), vec2(lo.x, hi.y), vec2(hi.x, hi.y));
    for (int i = 0; i < 4; ++i) {
        gl_Position = vec4(clamp(corners[i], vec2(0.0), vec2(size)) / size * 2.0 - 1.0, 0.0, 1.0);
        EmitVertex();
    }
    EndPrimitive();
}
