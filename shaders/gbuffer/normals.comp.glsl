// Brings host normals to the G-buffer contract (view space, unit, facing the camera), or
// reconstructs them from depth when the host has none (FROM_DEPTH).
//! variant: FROM_DEPTH
//! variant: UNSIGNED_ENCODING WORLD_SPACE
#include "../common/depth.glsl"
#include "../common/math.glsl"
#include "gbuffer_bindings.h"

layout(local_size_x = GBUFFER_WORKGROUP_SIZE, local_size_y = GBUFFER_WORKGROUP_SIZE) in;
layout(binding = GBUFFER_DEPTH_TEXTURE_UNIT) uniform sampler2D depthTexture;
#ifndef FROM_DEPTH
layout(binding = GBUFFER_NORMAL_TEXTURE_UNIT) uniform sampler2D normalTexture;
#endif
layout(binding = GBUFFER_OUTPUT_IMAGE_UNIT, rgba16f) writeonly uniform image2D normals;

#ifdef FROM_DEPTH
// Position of a neighbour, or `valid = false` outside the image or on background.
vec3 neighbour(ivec2 pixel, out bool valid) {
    valid = all(greaterThanEqual(pixel, ivec2(0))) && all(lessThan(pixel, frameSize()));
    if (!valid) return vec3(0.0);
    float d = texelFetch(depthTexture, pixel, 0).r;
    valid = !isBackground(d);
    return valid ? viewPositionFromDepth(pixelCenterUv(pixel), d) : vec3(0.0);
}

// Of the two one-sided differences along an axis, the one with the smaller depth step
// stays on the same surface at silhouettes.
vec3 tangent(ivec2 pixel, ivec2 axis, vec3 p) {
    bool okPlus, okMinus;
    vec3 plus = neighbour(pixel + axis, okPlus);
    vec3 minus = neighbour(pixel - axis, okMinus);
    if (okPlus && (!okMinus || abs(plus.z - p.z) <= abs(p.z - minus.z))) return plus - p;
    if (okMinus) return p - minus;
    return vec3(0.0);
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
    vec3 p = viewPositionFromDepth(pixelCenterUv(pixel), depth);
    vec3 toCamera = viewDirectionTo(p);
#ifdef FROM_DEPTH
    vec3 n = cross(tangent(pixel, ivec2(1, 0), p), tangent(pixel, ivec2(0, 1), p));
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
    if (dot(n, toCamera) < 0.0) n = -n;
    imageStore(normals, pixel, vec4(n, 1.0));
}
