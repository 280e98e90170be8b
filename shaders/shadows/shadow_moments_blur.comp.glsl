// One direction of the separable Gaussian over moment maps (sigma = radius / 2, taps clamped
// at the map's edges). ESM's log-space moment is blurred as log(sum w e^(c t)), shifted by
// the largest tap so that no exponential overflows.
//! variant: FILTER=2
//! variant: FILTER=3
//! variant: FILTER=3 MOMENTS_HALF
//! variant: FILTER=2 MOMENTS_UNORM
#include "shadow_bindings.h"

#ifndef FILTER
#define FILTER SHADOW_FILTER_VSM
#endif

layout(local_size_x = SHADOW_WORKGROUP, local_size_y = SHADOW_WORKGROUP) in;
layout(binding = SHADOW_MOMENTS_READ_IMAGE, SHADOW_MOMENT_FORMAT) readonly uniform image2DArray momentsIn;
layout(binding = SHADOW_MOMENTS_IMAGE, SHADOW_MOMENT_FORMAT) writeonly uniform image2DArray momentsOut;
layout(location = SHADOW_LOC_FILTER_PARAMS) uniform ivec2 blur;  // radius, direction (0: x, 1: y)
layout(location = SHADOW_LOC_LAYER_RANGE) uniform ivec2 layers; // first layer, maps

void main() {
    const ivec2 size = imageSize(momentsIn).xy;
    const ivec3 texel = ivec3(gl_GlobalInvocationID.xy, layers.x + int(gl_GlobalInvocationID.z));
    if (any(greaterThanEqual(texel.xy, size)) || int(gl_GlobalInvocationID.z) >= layers.y) return;
    const ivec2 step = blur.y == 0 ? ivec2(1, 0) : ivec2(0, 1);
    const float sigma = max(0.5 * float(blur.x), 1e-3);
    vec4 sum = vec4(0.0);
    float total = 0.0, largest = -3.0e38;
#if FILTER == SHADOW_FILTER_ESM
    for (int i = -blur.x; i <= blur.x; ++i)
        largest = max(largest, imageLoad(momentsIn, ivec3(clamp(texel.xy + step * i, ivec2(0), size - 1), texel.z)).x);
#endif
    for (int i = -blur.x; i <= blur.x; ++i) {
        const float w = exp(-0.5 * float(i * i) / (sigma * sigma));
        const vec4 m = imageLoad(momentsIn, ivec3(clamp(texel.xy + step * i, ivec2(0), size - 1), texel.z));
#if FILTER == SHADOW_FILTER_ESM
        sum.x += w * exp(m.x - largest);
#else
        sum += w * m;
#endif
        total += w;
    }
#if FILTER == SHADOW_FILTER_ESM
    imageStore(momentsOut, texel, vec4(largest + log(sum.x / total), 0.0, 0.0, 0.0));
#else
    imageStore(momentsOut, texel, sum / total);
#endif
}
