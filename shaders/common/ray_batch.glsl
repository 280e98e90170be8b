// Ray batches (src/core/ray_batches.hpp): an integrator's invocation runs the rays (or
// slices) [first, end) of its pixel's n; partial sums of earlier batches wait in a buffer,
// one entry per invocation: the pixel at the integrator's resolution, or (REFINE) the
// listed pixel's index. Needs refine_list.glsl before it.
#ifndef OBSCURA_RAY_BATCH_GLSL
#define OBSCURA_RAY_BATCH_GLSL
#include "common_bindings.h"

// x: first, y: end, z: 1 = earlier batches left partial sums, w: 1 = the last batch.
layout(location = OBSCURA_LOC_RAY_BATCH) uniform ivec4 rayBatch;

struct RayBatchPartial {
    vec4 a, b;
};

layout(std430, binding = OBSCURA_RAY_BATCH_SSBO) buffer RayBatchPartials {
    RayBatchPartial rayBatchPartials[];
};

uint rayBatchFirst() { return uint(rayBatch.x); }
uint rayBatchEnd() { return uint(rayBatch.y); }
bool rayBatchContinues() { return rayBatch.z != 0; }
bool rayBatchLast() { return rayBatch.w != 0; }

uint rayBatchSlot(ivec2 pixel, ivec2 size) {
#ifdef REFINE
    return gl_WorkGroupID.x * uint(FILTER_REFINE_GROUP) + gl_LocalInvocationIndex;
#else
    return uint(pixel.y) * uint(size.x) + uint(pixel.x);
#endif
}

// The sums so far: this batch's plus the earlier ones'.
RayBatchPartial rayBatchMerged(uint slot, RayBatchPartial own) {
    if (!rayBatchContinues()) return own;
    const RayBatchPartial earlier = rayBatchPartials[slot];
    return RayBatchPartial(earlier.a + own.a, earlier.b + own.b);
}

void rayBatchKeep(uint slot, RayBatchPartial sums) { rayBatchPartials[slot] = sums; }
#endif
