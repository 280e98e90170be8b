// Batch screen-space visibility queries: one invocation per view-space segment, written as
// (hit, first hidden sample index, texel fetches, t bits).
//! variant: SCREEN_MARCH=0
//! variant: SCREEN_MARCH=1
//! variant: SCREEN_MARCH=2
//! variant: SCREEN_MARCH=0 SCREEN_PEELED
//! variant: SCREEN_MARCH=0 SCREEN_PEELED SCREEN_PEELED_OR_CONSTANT
//! variant: SCREEN_MARCH=1 SCREEN_PEELED
//! variant: SCREEN_MARCH=1 SCREEN_PEELED SCREEN_PEELED_OR_CONSTANT
//! variant: SCREEN_MARCH=2 SCREEN_PEELED
//! variant: SCREEN_MARCH=2 SCREEN_PEELED SCREEN_PEELED_OR_CONSTANT
#include "screen_march.glsl"

layout(local_size_x = VIS_WORKGROUP_1D) in;
layout(std430, binding = VIS_SEGMENTS_SSBO) readonly buffer Segments {
    vec4 segments[]; // from.xyz, to.xyz in consecutive pairs (view space)
};
layout(std430, binding = VIS_RESULTS_SSBO) writeonly buffer Results {
    uvec4 results[];
};
layout(location = VIS_LOC_STEPS) uniform int steps;
layout(location = VIS_LOC_JITTER) uniform float jitter;
layout(location = VIS_LOC_THICKNESS) uniform float thickness;
layout(location = VIS_LOC_COUNT) uniform uint count;
layout(location = VIS_LOC_FIRST) uniform uint first;

// A segment's start with the normal and normal error of the pixel it lies in (segments from
// surface points start in their own pixel); elsewhere no normal and the view's normalError.
// `fetches` counts the normal's fetch.
ScreenRayStart rayStartOf(vec3 from, inout uint fetches) {
    ivec2 pixel;
    if (screenPixelOf(from, pixel)) {
        fetches += 1u;
        const vec4 normalTexel = texelFetch(visNormal, pixel, 0);
        if (normalTexel.a > 0.0) return ScreenRayStart(from, normalTexel.xyz, storedNormalError(normalTexel));
    }
    return ScreenRayStart(from, vec3(0.0), storedNormalError());
}

void main() {
    const uint i = first + gl_GlobalInvocationID.x;
    if (i >= count) return;
    const vec3 from = segments[2 * i].xyz, to = segments[2 * i + 1].xyz;
    const vec3 d = to - from;
    float t = -1.0;
    uint fetches = 0u;
    if (allFinite(from) && allFinite(to)) {
        uint startFetches = 0u;
        const ScreenRayStart start = rayStartOf(from, startFetches);
        t = screenMarchSegment(start, d, steps, jitter, thickness, fetches);
        fetches += startFetches;
    }
    const bool hit = t >= 0.0;
    // The sample index back from t (exact: t = (j + jitter) / steps was computed that way).
    const int j = hit ? int(round(t * float(steps) - jitter)) : -1;
    results[i] = uvec4(hit ? 1u : 0u, hit ? uint(j) : 0xFFFFFFFFu, fetches, floatBitsToUint(hit ? t : 1.0));
}
