// The G-buffer pixels that joint bilateral upsampling could not fill from similar
// low-resolution neighbours, for the integrator to compute at full resolution: the
// upsampling appends them, then the integrator's REFINE variant is dispatched indirectly
// from the header, one invocation per listed pixel. The header starts as (0, 1, 1, 0); the
// count may pass the capacity, the group count never does. Without REFINE, only
// integratorPixel.
#ifndef OBSCURA_REFINE_LIST_GLSL
#define OBSCURA_REFINE_LIST_GLSL
#include "filter_bindings.h"

// An integrator's pixel within its workgroup of FILTER_WORKGROUP^2 pixels (the x and y of the
// invocation; z is its ray lane, ray_batch.glsl).
uint integratorGroupPixel() { return gl_LocalInvocationID.y * uint(FILTER_WORKGROUP) + gl_LocalInvocationID.x; }

#ifdef REFINE

layout(std430, binding = FILTER_REFINE_SSBO) buffer RefineList {
    uint refineGroups[3]; // glDispatchComputeIndirect's arguments
    uint refineCount;     // appends tried
    uint refinePixels[];  // x | y << 16
};

uint refineCapacity() { return uint(refinePixels.length()); }

// Lists a G-buffer pixel; false when the list is full (the caller fills it itself).
bool refineAppend(ivec2 pixel) {
    const uint i = atomicAdd(refineCount, 1u);
    if (i >= refineCapacity()) return false;
    refinePixels[i] = uint(pixel.x) | (uint(pixel.y) << 16);
    if (i % uint(FILTER_REFINE_GROUP) == 0u) atomicAdd(refineGroups[0], 1u);
    return true;
}

// The listed pixel of this invocation (groups of FILTER_REFINE_GROUP, in list order); false
// past the list's end.
bool refinePixel(out ivec2 pixel) {
    const uint i = gl_WorkGroupID.x * uint(FILTER_REFINE_GROUP) + integratorGroupPixel();
    const bool listed = i < min(refineCount, refineCapacity());
    const uint code = listed ? refinePixels[i] : 0u;
    pixel = ivec2(code & 0xFFFFu, code >> 16);
    return listed;
}
#endif

// The pixel an integrator's invocation computes and the G-buffer pixel it is computed at:
// at the reduced resolution `size`, the top-left G-buffer pixel of its block; REFINE: a
// listed G-buffer pixel, both, so that its noise is what a full-resolution run gives it.
// False: none (past the image or the list).
bool integratorPixel(ivec2 size, int scale, out ivec2 pixel, out ivec2 full) {
#ifdef REFINE
    const bool listed = refinePixel(pixel);
    full = pixel;
    return listed;
#else
    pixel = ivec2(gl_GlobalInvocationID.xy);
    full = min(pixel * scale, frameSize() - 1);
    return all(lessThan(pixel, size));
#endif
}
#endif
