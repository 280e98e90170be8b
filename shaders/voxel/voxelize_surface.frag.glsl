// Surface voxelization, step 2: the voxels of this pixel's column that the triangle's plane
// can reach are tested exactly (separating axes, Akenine-Moeller) and set with an atomic OR
// in a 32-slices-per-layer R32UI image (packed into the RGBA32UI slicemap afterwards).
#include "voxel_params.glsl"

flat in vec3 gA, gB, gC;
flat in ivec3 gOrigin;
flat in int gAxis;
flat in vec3 gPlane;
flat in float gGrow;

layout(binding = VOXEL_SCRATCH_IMAGE, r32ui) coherent uniform uimage2DArray slices;

// Float rounding may only add voxels: the box is grown by gGrow (about 1e-5 voxel; the CPU
// reference uses the exact box, so the GPU result is a superset of it).
bool separatedOnAxis(vec3 axis, vec3 v0, vec3 v1, vec3 v2, float halfSize) {
    const float p0 = dot(axis, v0), p1 = dot(axis, v1), p2 = dot(axis, v2);
    const float r = halfSize * (abs(axis.x) + abs(axis.y) + abs(axis.z));
    return min(p0, min(p1, p2)) > r || max(p0, max(p1, p2)) < -r;
}

// Triangle/box overlap for the unit voxel with corner `cell` (relative to gOrigin), by the
// separating axis theorem: the 3 box normals, the triangle normal, the 9 edge cross products.
bool overlaps(vec3 cell) {
    const float halfSize = 0.5 + gGrow;
    const vec3 centre = cell + 0.5;
    const vec3 v0 = gA - centre, v1 = gB - centre, v2 = gC - centre;
    if (any(greaterThan(min(v0, min(v1, v2)), vec3(halfSize))) || any(lessThan(max(v0, max(v1, v2)), vec3(-halfSize))))
        return false;
    const vec3 e0 = v1 - v0, e1 = v2 - v1, e2 = v0 - v2;
    if (separatedOnAxis(cross(e0, e1), v0, v1, v2, halfSize)) return false;
    const vec3 axes[3] = vec3[3](vec3(1, 0, 0), vec3(0, 1, 0), vec3(0, 0, 1));
    for (int i = 0; i < 3; ++i) {
        if (separatedOnAxis(cross(axes[i], e0), v0, v1, v2, halfSize)) return false;
        if (separatedOnAxis(cross(axes[i], e1), v0, v1, v2, halfSize)) return false;
        if (separatedOnAxis(cross(axes[i], e2), v0, v1, v2, halfSize)) return false;
    }
    return true;
}

// (u, v, w) back to (x, y, z), and (x, y, z) to (u, v, w) (see the geometry shader).
ivec3 unpermute(ivec3 p, int axis) { return axis == 0 ? p.zxy : (axis == 1 ? p.yzx : p); }
ivec3 permute(ivec3 p, int axis) { return axis == 0 ? p.yzx : (axis == 1 ? p.zxy : p); }

void main() {
    const ivec2 uv = ivec2(gl_FragCoord.xy);
    const ivec3 size = permute(voxel.dims, gAxis);
    if (uv.x >= size.x || uv.y >= size.y) return;
    const vec2 local = vec2(uv - gOrigin.xy); // this column's corner, triangle-relative
    // The plane's depth over this pixel's square (slopes from the geometry shader, at most 1
    // along the dominant axis: a few voxels at most), clamped to the triangle's own depth
    // range. A zero-area triangle has no plane: its whole depth range is tested.
    const float wMin = min(gA.z, min(gB.z, gC.z)), wMax = max(gA.z, max(gB.z, gC.z));
    float pMin = wMin, pMax = wMax;
    if (gPlane.z != 0.0) {
        pMin = 1e30;
        pMax = -1e30;
        for (int i = 0; i < 4; ++i) {
            const vec2 corner = local + vec2(i & 1, i >> 1);
            const float w = gA.z + gPlane.x * (corner.x - gA.x) + gPlane.y * (corner.y - gA.y);
            pMin = min(pMin, w);
            pMax = max(pMax, w);
        }
    }
    const int first = max(int(floor(max(pMin, wMin) - 2.0 * gGrow)) + gOrigin.z, 0);
    const int last = min(int(floor(min(pMax, wMax) + 2.0 * gGrow)) + gOrigin.z, size.z - 1);
    for (int w = first; w <= last; ++w) {
        if (!overlaps(vec3(local, float(w - gOrigin.z)))) continue;
        const ivec3 p = unpermute(ivec3(uv, w), gAxis);
        imageAtomicOr(slices, ivec3(p.xy, p.z >> 5), 1u << uint(p.z & 31));
    }
}
