// Surface voxelization, step 1: each triangle is projected along its dominant axis (so no
// triangle is seen edge-on) and replaced by its 2D bounding box grown by one pixel, so every
// voxel column it touches gets a fragment (conservative rasterization without hardware
// support; the fragment shader then tests each candidate voxel exactly).
//
// A triangle reaching more than a voxel outside the grid is first clipped to the grid (grown
// by a voxel) in double precision and voxelized as the fan of its clipped polygon: the same
// voxels, with coordinates small enough for the float test.
#include "voxel_params.glsl"

layout(triangles) in;
// Up to 7 fan triangles of the clipped polygon, a 4-vertex strip each.
layout(triangle_strip, max_vertices = 28) out;

in dvec3 vVoxel[];
// The triangle in projected (u, v, w) voxel coordinates relative to the integer corner
// gOrigin: float keeps 24 bits of the triangle's own extent, not of its place in the grid.
flat out vec3 gA, gB, gC;
flat out ivec3 gOrigin;
flat out int gAxis;   // the projection axis (w): 0 = x, 1 = y, 2 = z
flat out vec3 gPlane; // w = gA.z + x (u - gA.x) + y (v - gA.y); z = 0: zero area, no plane
flat out float gGrow; // how far the voxel boxes are grown against float rounding, voxels

const int kMaxPolygon = 9; // a triangle clipped by 6 planes

// (u, v, w) with w along the axis; u, v the image plane.
dvec3 permute(dvec3 p, int axis) { return axis == 0 ? p.yzx : (axis == 1 ? p.zxy : p); }

bool finite(dvec3 p) { return !any(isnan(p)) && !any(isinf(p)); }

// Emits one (piece of the) triangle, already permuted, as its grown bounding-box quad.
void emitTriangle(dvec3 pa, dvec3 pb, dvec3 pc, int axis, vec3 plane) {
    const dvec3 origin = floor(min(pa, min(pb, pc)));
    const vec3 a = vec3(pa - origin), b = vec3(pb - origin), c = vec3(pc - origin);
    // The separating-axis test's float error grows with the piece's extent E (its
    // coordinates here are in [0, E]): a few ulp of E, plus a floor for tiny triangles.
    const vec3 extent = max(a, max(b, c));
    const float grow = 1e-5 + 8.0 * max(extent.x, max(extent.y, extent.z)) / 16777216.0;
    const vec2 lo = vec2(origin.xy) + floor(min(a.xy, min(b.xy, c.xy))) - 1.0;
    const vec2 hi = vec2(origin.xy) + ceil(max(a.xy, max(b.xy, c.xy))) + 1.0;
    const float size = float(voxel.surfaceViewport);
    const vec2 corners[4] = vec2[4](vec2(lo.x, lo.y), vec2(hi.x, lo.y), vec2(lo.x, hi.y), vec2(hi.x, hi.y));
    for (int i = 0; i < 4; ++i) {
        // Every output again before each vertex: EmitVertex leaves them undefined (GLSL 4.50
        // 8.16), and the strip's provoking vertices are its later ones.
        gA = a;
        gB = b;
        gC = c;
        gOrigin = ivec3(origin); // within the grid grown by two voxels: no overflow
        gAxis = axis;
        gPlane = plane;
        gGrow = grow;
        gl_Position = vec4(clamp(corners[i], vec2(0.0), vec2(size)) / size * 2.0 - 1.0, 0.0, 1.0);
        EmitVertex();
    }
    EndPrimitive();
}

void main() {
    const dvec3 a = vVoxel[0], b = vVoxel[1], c = vVoxel[2];
    if (!finite(a) || !finite(b) || !finite(c)) return;
    const dvec3 n = cross(b - a, c - a), an = abs(n);
    int axis = (an.x >= an.y && an.x >= an.z) ? 0 : (an.y >= an.z ? 1 : 2);
    vec3 plane = vec3(0.0);
    if (max(an.x, max(an.y, an.z)) == 0.0) {
        // Zero area: a segment or a point, voxelized as such (the separating axis test
        // handles it). Project along the axis of least extent, so it is not seen end-on.
        const dvec3 extent = max(a, max(b, c)) - min(a, min(b, c));
        axis = (extent.x <= extent.y && extent.x <= extent.z) ? 0 : (extent.y <= extent.z ? 1 : 2);
    } else {
        // The plane's depth slopes in double (|slope| <= 1 along the dominant axis), so
        // slivers keep an accurate plane.
        const dvec3 pn = permute(n, axis);
        plane = vec3(vec2(-pn.xy / pn.z), 1.0);
    }
    const dvec3 lo = dvec3(-1.0), hi = dvec3(voxel.dims) + 1.0;
    const dvec3 boxMin = min(a, min(b, c)), boxMax = max(a, max(b, c));
    if (any(greaterThan(boxMin, hi)) || any(lessThan(boxMax, lo))) return; // touches no voxel
    if (all(greaterThanEqual(boxMin, lo)) && all(lessThanEqual(boxMax, hi))) {
        emitTriangle(permute(a, axis), permute(b, axis), permute(c, axis), axis, plane);
        return;
    }
    // Sutherland-Hodgman against the six faces of [lo, hi].
    dvec3 polygon[kMaxPolygon] = dvec3[kMaxPolygon](a, b, c, a, a, a, a, a, a);
    int count = 3;
    for (int face = 0; face < 6 && count > 0; ++face) {
        const int k = face >> 1;
        const double bound = (face & 1) == 0 ? lo[k] : hi[k];
        const double side = (face & 1) == 0 ? 1.0 : -1.0; // inside: side * (p[k] - bound) >= 0
        dvec3 clipped[kMaxPolygon];
        int kept = 0;
        for (int i = 0; i < count; ++i) {
            const dvec3 p = polygon[i], q = polygon[(i + 1) % count];
            const double dp = side * (p[k] - bound), dq = side * (q[k] - bound);
            if (dp >= 0.0 && kept < kMaxPolygon) clipped[kept++] = p;
            if ((dp < 0.0) != (dq < 0.0) && kept < kMaxPolygon) {
                // Exactly on the face. (Not x[k] = bound: NVIDIA's 580 driver fails to link
                // a dynamically indexed write into a dvec3, "can't find __setVectorIndex".)
                const dvec3 x = mix(p, q, dp / (dp - dq));
                clipped[kept++] = mix(x, dvec3(bound), equal(ivec3(k), ivec3(0, 1, 2)));
            }
        }
        count = kept;
        for (int i = 0; i < count; ++i) polygon[i] = clipped[i];
    }
    for (int i = 1; i + 1 < count; ++i)
        emitTriangle(permute(polygon[0], axis), permute(polygon[i], axis), permute(polygon[i + 1], axis), axis, plane);
}
