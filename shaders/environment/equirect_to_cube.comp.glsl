// The cube map's level 0 from the equirectangular source: one invocation per cube texel,
// reading the source at the level whose texels are about the cube texel's size, so that a
// large source is averaged rather than point-sampled. Directions are the environment's own
// frame (rotation 0); the GL cube face conventions (OpenGL 4.5, 8.13).
//! variant:
#include "../common/math.glsl"
#include "environment_bindings.h"

layout(local_size_x = ENV_WORKGROUP, local_size_y = ENV_WORKGROUP, local_size_z = 1) in;
layout(binding = ENV_SOURCE_UNIT) uniform sampler2D source;
layout(binding = ENV_CUBE_OUT_IMAGE, rgba16f) writeonly uniform imageCube cubeOut;
layout(location = 0) uniform int cubeSize;

vec3 cubeDirection(int face, vec2 st) {
    switch (face) {
    case 0: return vec3(1.0, -st.y, -st.x);
    case 1: return vec3(-1.0, -st.y, st.x);
    case 2: return vec3(st.x, 1.0, st.y);
    case 3: return vec3(st.x, -1.0, -st.y);
    case 4: return vec3(st.x, -st.y, 1.0);
    default: return vec3(-st.x, -st.y, -1.0);
    }
}

void main() {
    const ivec3 id = ivec3(gl_GlobalInvocationID);
    if (id.x >= cubeSize || id.y >= cubeSize) return;
    const vec2 st = 2.0 * (vec2(id.xy) + 0.5) / float(cubeSize) - 1.0;
    const vec3 w = normalize(cubeDirection(id.z, st));
    // src/reference/environment.cpp's toUv at rotation 0.
    const float u = atan(w.x, -w.z) / (2.0 * OBSCURA_PI) + 0.5;
    const float v = acos(clamp(w.y, -1.0, 1.0)) / OBSCURA_PI;
    // Source texels per cube texel, along the equator: 2 pi / width against pi/2 / cubeSize.
    const float ratio = float(textureSize(source, 0).x) / (4.0 * float(cubeSize));
    const float level = max(log2(max(ratio, 1.0)), 0.0);
    imageStore(cubeOut, ivec3(id.xy, id.z), vec4(max(textureLod(source, vec2(u, v), level).rgb, vec3(0.0)), 1.0));
}
