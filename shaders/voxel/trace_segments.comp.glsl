// Batch visibility queries: one invocation per segment (voxel-space endpoints), written as
// (hit, t bits, fetches, packed voxel); METHOD 3 answers point occupancy at `from`.
//! variant: METHOD=0
//! variant: METHOD=1
//! variant: METHOD=2
//! variant: METHOD=3
#include "voxel_traversal.glsl"

layout(local_size_x = VOXEL_WORKGROUP_1D) in;
layout(std430, binding = VOXEL_SEGMENTS_SSBO) readonly buffer Segments {
    vec4 segments[]; // from.xyz, to.xyz in consecutive pairs
};
layout(std430, binding = VOXEL_RESULTS_SSBO) writeonly buffer Results {
    uvec4 results[];
};
layout(location = VOXEL_LOC_STEPS) uniform int steps;
layout(location = VOXEL_LOC_SEED) uniform uint seed;
layout(location = VOXEL_LOC_COUNT) uniform uint count;
layout(location = VOXEL_LOC_FIRST) uniform uint first;

// A per-segment jitter in [0, 1) (integer hash, Wang 1997).
float jitterOf(uint i) {
    uint h = i ^ seed;
    h = (h ^ 61u) ^ (h >> 16);
    h *= 9u;
    h ^= h >> 4;
    h *= 0x27d4eb2du;
    h ^= h >> 15;
    return float(h >> 8) / 16777216.0;
}

void main() {
    const uint i = first + gl_GlobalInvocationID.x;
    if (i >= count) return;
    const vec3 from = segments[2 * i].xyz, to = segments[2 * i + 1].xyz;
#if METHOD == VOXEL_METHOD_MARCH
    const VoxelHit h = voxelTraceMarch(from, to, steps, jitterOf(i));
#elif METHOD == VOXEL_METHOD_EXACT
    const VoxelHit h = voxelTraceExact(from, to);
#elif METHOD == VOXEL_METHOD_HIERARCHICAL
    const VoxelHit h = voxelTraceHierarchical(from, to);
#else
    VoxelHit h = voxelMiss();
    h.hit = voxelOccupiedAtPoint(from);
#endif
    const uint voxelIndex = h.hit ? (uint(h.voxel.x) | (uint(h.voxel.y) << 11) | (uint(h.voxel.z) << 22)) : 0xFFFFFFFFu;
    results[i] = uvec4(h.hit ? 1u : 0u, floatBitsToUint(h.t), h.fetches, voxelIndex);
}
