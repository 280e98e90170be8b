// Paraboloid projection of one triangle: clipped to the map's hemisphere (z >= 0) in 3D,
// where clipping is exact, then each corner projected to (x, y) / (|p| + z). Outside the
// hemisphere a corner's projection runs off to infinity, so clipping after it would not do.
// The fragment shader gets the triangle's plane to correct its depth.
#include "shadow_bindings.h"

layout(triangles) in;
layout(triangle_strip, max_vertices = 4) out;

in vec3 vMap[];
flat out vec4 gPlane;      // unit normal n and offset e: n . p = e for p on the triangle's plane
noperspective out vec3 gPoint; // the corners interpolated linearly on the map: a fallback

void emitCorner(vec3 p, vec4 plane) {
    gPlane = plane;
    gPoint = p;
    // |p| + z > 0 in the hemisphere unless p is the light itself.
    gl_Position = vec4(p.xy / max(length(p) + p.z, 1e-30), 0.5, 1.0);
    EmitVertex();
}

// Where the edge a -> b crosses z = 0 (a.z and b.z on opposite sides).
vec3 rimPoint(vec3 a, vec3 b) { return mix(a, b, a.z / (a.z - b.z)); }

void main() {
    const vec3 a = vMap[0], b = vMap[1], c = vMap[2];
    const vec3 normal = cross(b - a, c - a);
    const float area = length(normal);
    const bool inA = a.z >= 0.0, inB = b.z >= 0.0, inC = c.z >= 0.0;
    const int inside = int(inA) + int(inB) + int(inC);
    const vec4 plane = vec4(normal / max(area, 1e-30), dot(normal / max(area, 1e-30), a));
    // A triangle whose plane passes through the light (within float rounding of its corners'
    // distance) is seen edge-on: it covers no directions. Drawn, its corners would all land
    // on the rim and its straight edges cover the map's inside with wrong depths: a rect
    // light flush with its ceiling, a point light on a wall.
    const float reach = max(length(a), max(length(b), length(c)));
    const bool edgeOn = abs(plane.w) <= 1e-5 * reach;
    // Degenerate triangles, edge-on ones and the other hemisphere draw nothing.
    if (area > 0.0 && inside > 0 && !edgeOn) {
        if (inside == 3) {
            emitCorner(a, plane);
            emitCorner(b, plane);
            emitCorner(c, plane);
        } else {
            // Rotate the corners so that p0 is the odd one out (alone inside, or alone outside).
            const bool aOdd = (inA != inB) && (inA != inC), bOdd = (inB != inA) && (inB != inC);
            const vec3 p0 = aOdd ? a : bOdd ? b : c, p1 = aOdd ? b : bOdd ? c : a, p2 = aOdd ? c : bOdd ? a : b;
            const vec3 q1 = rimPoint(p0, p1), q2 = rimPoint(p0, p2);
            if (inside == 1) { // p0 inside: one triangle
                emitCorner(p0, plane);
                emitCorner(q1, plane);
                emitCorner(q2, plane);
            } else { // p0 outside: the quad q1 p1 p2 q2 as a strip
                emitCorner(q1, plane);
                emitCorner(p1, plane);
                emitCorner(q2, plane);
                emitCorner(p2, plane);
            }
        }
        EndPrimitive();
    }
}
