// The G-buffer pixels that joint bilateral upsampling could not fill from similar
// low-resolution neighbours, for the integrator to compute at full resolution: the
// upsampling appends them, then the integrator's REFINE variant is dispatched indirectly
// from the header, one invocation per listed pixel. The header starts as (0, 1, 1, 0); the
// count may pass the capacity, the group count never does. When the count passes the
// capacity, no pixel is refined: which ones made the list depends on the order the GPU ran
// the upsampling's invocations, and a frame must not (they keep the upsampled value).
// Without REFINE, only integratorPixel.
#ifndef OBSCURA_REFINE_LIST_GLSL
#define OBSCURA_REFINE_LIST_GLSL
#include "filter_bindings.h"
#include "geometry_tiles.glsl"

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

// Lists the pixels of the quad at `quad` (p, p + (1, 0), p + (0, 1), p + (1, 1)) that are
// `wanted`, in that order, with one atomic add for all of them. On llvmpipe every SIMD batch
// runs each atomic and store lane by lane, masked off or not: the appends took about 3 of the
// upsampling's 11 ms on the Cornell box at 512 x 512, and one add a quad instead of one a
// pixel saved about 1.2 ms.
void refineAppendQuad(ivec2 quad, bvec4 wanted) {
    const uvec4 want = uvec4(wanted);
    const uint n = want.x + want.y + want.z + want.w;
    if (n > 0u) {
        const uint first = atomicAdd(refineCount, n), end = min(first + n, refineCapacity());
        // The groups the list's length now starts: the multiples of the group size in [first, end).
        const uint group = uint(FILTER_REFINE_GROUP), firstStart = (first + group - 1u) / group * group;
        if (firstStart < end) atomicAdd(refineGroups[0], (end - 1u - firstStart) / group + 1u);
        const uvec4 slot = first + uvec4(0u, want.x, want.x + want.y, want.x + want.y + want.z); // in list order
        const bvec4 listed = bvec4(uvec4(wanted) * uvec4(lessThan(slot, uvec4(end))));
        for (int k = 0; k < 4; ++k)
            if (listed[k]) refinePixels[slot[k]] = uint(quad.x + (k & 1)) | (uint(quad.y + (k >> 1)) << 16);
    }
}

// The listed pixel of this invocation (groups of FILTER_REFINE_GROUP, in list order); false
// past the list's end, and for every invocation when the list overflowed.
bool refinePixel(out ivec2 pixel) {
    const uint i = gl_WorkGroupID.x * uint(FILTER_REFINE_GROUP) + integratorGroupPixel();
    const bool listed = refineCount <= refineCapacity() && i < refineCount;
    const uint code = listed ? refinePixels[i] : 0u;
    pixel = ivec2(code & 0xFFFFu, code >> 16);
    return listed;
}
#endif

// The pixel an integrator's invocation computes and the G-buffer pixel it is computed at:
// at the reduced resolution `size`, the top-left G-buffer pixel of its block (TILES: one of
// a listed tile's pixels with geometry there, geometry_tiles.glsl); REFINE: a listed
// G-buffer pixel, both, so that its noise is what a full-resolution run gives it. False:
// none (past the image or the list).
bool integratorPixel(ivec2 size, int scale, out ivec2 pixel, out ivec2 full) {
#ifdef REFINE
    const bool listed = refinePixel(pixel);
    full = pixel;
    return listed;
#else
#ifdef TILES
    const bool listed = tiledGeometryPixel(frameSize(), scale, integratorGroupPixel(), pixel);
#else
    const bool listed = true;
    pixel = ivec2(gl_GlobalInvocationID.xy);
#endif
    full = min(pixel * scale, frameSize() - 1);
    return listed && all(lessThan(pixel, size));
#endif
}
#endif
