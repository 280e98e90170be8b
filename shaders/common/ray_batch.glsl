// Ray batches (src/core/ray_batches.hpp): an integrator's invocation runs the rays (or
// slices) [first, end) of its pixel's n; partial sums of earlier batches wait in a buffer,
// one entry per pixel: the pixel at the integrator's resolution, or (REFINE) the
// listed pixel's index. Needs refine_list.glsl before it.
//
// Ray lanes: RAY_LANES invocations (a power of two, 1 to 16; the workgroup's z size) share
// one pixel's rays: lane k takes rays first + k, first + k + RAY_LANES, ... and lane 0 adds
// the others' sums (rayLanesSum) and finishes the pixel. A pixel's rays otherwise run one
// after another in one invocation, so a pass over few pixels (the refinement's list, a
// reduced resolution, a small object) lasts as long as its slowest pixel's rays, however
// many threads the device has free.
#ifndef OBSCURA_RAY_BATCH_GLSL
#define OBSCURA_RAY_BATCH_GLSL
#include "common_bindings.h"
#ifndef RAY_LANES
#define RAY_LANES 1
#endif
#if RAY_LANES < 1 || RAY_LANES > 16 || (RAY_LANES & (RAY_LANES - 1)) != 0
#error "RAY_LANES must be 1, 2, 4, 8 or 16"
#endif

// x: first, y: end, z: 1 = earlier batches left partial sums, w: 1 = the last batch.
layout(location = OBSCURA_LOC_RAY_BATCH) uniform ivec4 rayBatch;

struct RayBatchPartial {
    vec4 a, b;
};

layout(std430, binding = OBSCURA_RAY_BATCH_SSBO) buffer RayBatchPartials {
    RayBatchPartial rayBatchPartials[];
};

uint rayLane() { return RAY_LANES > 1 ? gl_LocalInvocationID.z : 0u; }
// This lane's first ray of the batch; the next is RAY_LANES later.
uint rayBatchFirst() { return uint(rayBatch.x) + rayLane(); }
uint rayBatchEnd() { return uint(rayBatch.y); }
bool rayBatchContinues() { return rayBatch.z != 0; }
bool rayBatchLast() { return rayBatch.w != 0; }

uint rayBatchSlot(ivec2 pixel, ivec2 size) {
#ifdef REFINE
    return gl_WorkGroupID.x * uint(FILTER_REFINE_GROUP) + integratorGroupPixel();
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

#if RAY_LANES > 1
// Lanes 1 to RAY_LANES - 1 of the group's FILTER_REFINE_GROUP pixels (32 bytes each: at 16
// lanes 30 KiB, within the 32 KiB every GL 4.5 implementation offers).
shared RayBatchPartial rayLanePartials[(RAY_LANES - 1) * FILTER_REFINE_GROUP];
#endif

// The sums of all the pixel's lanes, in lane order (the same result every run), for lane 0;
// the others get their own. Every invocation of the group must call it (a barrier).
RayBatchPartial rayLanesSum(RayBatchPartial own) {
#if RAY_LANES > 1
    const uint pixel = integratorGroupPixel();
    if (rayLane() > 0u) rayLanePartials[(rayLane() - 1u) * uint(FILTER_REFINE_GROUP) + pixel] = own;
    memoryBarrierShared();
    barrier();
    if (rayLane() == 0u) {
        for (uint k = 0u; k < uint(RAY_LANES - 1); ++k) {
            const RayBatchPartial other = rayLanePartials[k * uint(FILTER_REFINE_GROUP) + pixel];
            own = RayBatchPartial(own.a + other.a, own.b + other.b);
        }
    }
#endif
    return own;
}
#endif
