// Temporal accumulation of a result at the G-buffer's resolution (AO, or with RGB indirect
// light): each pixel's value is averaged with its history, the last frame's accumulated value
// at the same surface point, reprojected through the last frame's view-projection and read
// bilinearly from the four texels around it. A texel whose stored surface is not this point's
// is left out: its point (rebuilt from its stored view depth) off this point's tangent plane
// by more than the relative tolerance of its depth, or its normal further from this point's
// than the threshold. What the camera newly sees starts afresh instead of ghosting. (The
// plane, not the depth alone: on a surface seen at a grazing angle the depth changes by more
// than a few per cent between a point and its texel's centre.) The history counts its frames n (alpha); the new value is
// history + (current - history) / min(n + 1, most frames): the plain mean of up to that many
// frames, then an exponential average with weight 1 / most frames.
//! variant: RGB
#include "../common/depth.glsl"
#include "filter_bindings.h"
#include "../visibility/visibility_bindings.h"

layout(local_size_x = FILTER_WORKGROUP, local_size_y = FILTER_WORKGROUP) in;
layout(binding = VIS_DEPTH_UNIT) uniform sampler2D gDepth;
layout(binding = VIS_NORMAL_UNIT) uniform sampler2D gNormal;
// imageLoad, not texelFetch: the same texels, a fraction of the cost on llvmpipe (filter_bindings.h).
layout(binding = TEMPORAL_HISTORY_IMAGE, rgba16f) readonly uniform image2D history;
layout(binding = TEMPORAL_GEOMETRY_IMAGE, rg32ui) readonly uniform uimage2D historyGeometry;
#ifdef RGB
layout(binding = TEMPORAL_VALUE_IMAGE, rgba16f) uniform image2D value;
#else
layout(binding = TEMPORAL_VALUE_IMAGE, r16f) uniform image2D value;
#endif
layout(binding = TEMPORAL_HISTORY_OUT_IMAGE, rgba16f) writeonly uniform image2D historyOut;
layout(binding = TEMPORAL_GEOMETRY_OUT_IMAGE, rg32ui) writeonly uniform uimage2D geometryOut;
layout(std140, binding = TEMPORAL_PARAMS_UBO_BINDING) uniform TemporalBlock {
    TemporalParams temporal;
};

// Octahedral encoding of a unit vector in [-1, 1]^2 (Meyer et al. 2010), 16 bits a component.
vec2 octahedral(vec3 n) {
    n /= abs(n.x) + abs(n.y) + abs(n.z);
    const vec2 folded = (1.0 - abs(n.yx)) * vec2(n.x >= 0.0 ? 1.0 : -1.0, n.y >= 0.0 ? 1.0 : -1.0);
    return n.z >= 0.0 ? n.xy : folded;
}
vec3 fromOctahedral(vec2 e) {
    vec3 n = vec3(e, 1.0 - abs(e.x) - abs(e.y));
    if (n.z < 0.0) n.xy = (1.0 - abs(n.yx)) * vec2(n.x >= 0.0 ? 1.0 : -1.0, n.y >= 0.0 ? 1.0 : -1.0);
    return normalize(n);
}

// A texel's point in the last frame's view space, from its stored view depth (-z).
vec3 previousViewPoint(ivec2 texel, float depth) {
    const vec2 ndc = (vec2(texel) + 0.5) / vec2(frameSize()) * 2.0 - 1.0;
    const vec2 xy = ndc * temporal.previousRayScale + temporal.previousRayOffset;
    return vec3(temporal.previousPerspective != 0 ? xy * depth : xy, -depth);
}

void main() {
    const ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(pixel, frameSize()))) return;
    const vec4 current = imageLoad(value, pixel);
    const float depth = texelFetch(gDepth, pixel, 0).r;
    const vec4 normalTexel = texelFetch(gNormal, pixel, 0);
    if (isBackground(depth) || normalTexel.a == 0.0) {
        imageStore(historyOut, pixel, vec4(current.rgb, 0.0));
        imageStore(geometryOut, pixel, uvec4(0u));
        return;
    }
    const vec3 p = viewPositionFromDepth(pixelCenterUv(pixel), depth);
    const vec3 world = (frame.viewInverse * vec4(p, 1.0)).xyz;
    const vec3 worldNormal = normalize(mat3(frame.viewInverse) * normalTexel.xyz);

    vec4 sum = vec4(0.0);
    float weight = 0.0;
    const vec4 clip = temporal.previousViewProjection * vec4(world, 1.0);
    const vec3 previous = (temporal.previousView * vec4(world, 1.0)).xyz; // this point in the last frame's view
    const vec3 previousNormal = mat3(temporal.previousView) * worldNormal;
    if (temporal.hasHistory != 0 && clip.w > 0.0 && previous.z < 0.0) {
        const vec2 texel = (clip.xy / clip.w * 0.5 + 0.5) * vec2(frameSize()) - 0.5;
        const ivec2 base = ivec2(floor(texel));
        const vec2 f = texel - vec2(base);
        for (int k = 0; k < 4; ++k) {
            const ivec2 offset = ivec2(k & 1, k >> 1);
            const ivec2 q = base + offset;
            if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, frameSize()))) continue;
            const uvec2 geometry = imageLoad(historyGeometry, q).rg;
            const float storedDepth = uintBitsToFloat(geometry.x);
            if (!(storedDepth > 0.0)) continue;
            const float offPlane = dot(previousViewPoint(q, storedDepth) - previous, previousNormal);
            if (!(abs(offPlane) <= temporal.depthTolerance * storedDepth)) continue;
            if (dot(fromOctahedral(unpackSnorm2x16(geometry.y)), worldNormal) < temporal.normalThreshold) continue;
            const float w = (offset.x == 1 ? f.x : 1.0 - f.x) * (offset.y == 1 ? f.y : 1.0 - f.y);
            sum += w * imageLoad(history, q);
            weight += w;
        }
    }
    // A history read from texels of little bilinear weight is more its neighbours' than this
    // point's: kept only above a quarter of the full weight.
    const bool kept = weight > 0.25;
    const vec4 old = kept ? sum / weight : vec4(0.0);
    const float frames = min((kept ? old.a : 0.0) + 1.0, temporal.maxFrames);
    const vec3 accumulated = kept ? old.rgb + (current.rgb - old.rgb) / frames : current.rgb;
    imageStore(value, pixel, vec4(accumulated, current.a));
    imageStore(historyOut, pixel, vec4(accumulated, frames));
    imageStore(geometryOut, pixel, uvec4(floatBitsToUint(-p.z), packSnorm2x16(octahedral(worldNormal)), 0u, 0u));
}
