// A triangle covering the viewport; uv spans [0, 1]^2 over it.
out vec2 vUv;

void main() {
    const vec2 corner = vec2((gl_VertexID << 1) & 2, gl_VertexID & 2);
    vUv = corner;
    gl_Position = vec4(corner * 2.0 - 1.0, 0.0, 1.0);
}
