// Computes the exact face (geometric) normal of each triangle from its view-space vertices,
// turned toward the camera (and whether the camera sees the counter-clockwise, emitting
// side), and drops triangles that cannot be shaded: non-finite vertices
// (NaN/Inf in a host buffer) and zero-area triangles, whose normal is undefined.
#include "../common/frame.glsl"
#include "../common/math.glsl"

layout(triangles) in;
layout(triangle_strip, max_vertices = 3) out;

in VertexData {
    vec3 viewPosition;
    vec3 viewNormal;
    vec2 texcoord;
} gin[];

invariant gl_Position;

out FragmentData {
    vec3 viewPosition;
    vec3 shadingNormal;
    vec2 texcoord;
    flat vec3 faceNormal;
    flat float frontSide; // 1 when the camera sees the counter-clockwise side (emission), else 0
} gout;

void main() {
    vec3 p0 = gin[0].viewPosition, p1 = gin[1].viewPosition, p2 = gin[2].viewPosition;
    if (!allFinite(p0) || !allFinite(p1) || !allFinite(p2)) return;
    // Scale the edges to O(1) before the cross product so it neither overflows for huge
    // triangles nor underflows for tiny ones.
    vec3 e1 = p1 - p0, e2 = p2 - p0;
    float scale = max(max(max(abs(e1.x), abs(e1.y)), abs(e1.z)), max(max(abs(e2.x), abs(e2.y)), abs(e2.z)));
    if (!(scale > 0.0) || isinf(scale)) return;
    vec3 n = safeNormalize(cross(e1 / scale, e2 / scale), vec3(0.0));
    if (n == vec3(0.0)) return;
    // The plane's side facing the camera: n.p has one sign over the whole plane.
    vec3 toCamera = isPerspective() ? -p0 : vec3(0.0, 0.0, 1.0);
    const bool front = dot(n, toCamera) >= 0.0;
    if (!front) n = -n;

    for (int i = 0; i < 3; ++i) {
        gl_Position = gl_in[i].gl_Position;
        gout.viewPosition = gin[i].viewPosition;
        gout.shadingNormal = gin[i].viewNormal;
        gout.texcoord = gin[i].texcoord;
        gout.faceNormal = n;
        gout.frontSide = front ? 1.0 : 0.0;
        EmitVertex();
    }
    EndPrimitive();
}
