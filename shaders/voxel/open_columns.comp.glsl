// Solid voxelization's check for open (non-watertight) meshes: a column that crosses the
// mesh's surface an odd number of times (along the whole line, also outside the box) does not
// start and end outside the solid, which a closed surface cannot do. Such columns are
// cleared and counted.
#include "voxel_params.glsl"

layout(local_size_x = VOXEL_WORKGROUP_2D, local_size_y = VOXEL_WORKGROUP_2D) in;
layout(binding = VOXEL_OUT_IMAGE, rgba32ui) writeonly uniform uimage2DArray grid;
layout(binding = VOXEL_SCRATCH_IMAGE, r32ui) readonly uniform uimage2DArray parity;
layout(std430, binding = VOXEL_COUNTER_SSBO) buffer Counter {
    uint openColumns;
};

void main() {
    const ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(p, voxel.dims.xy))) return;
    if ((imageLoad(parity, ivec3(p, 0)).r & 1u) == 0u) return;
    atomicAdd(openColumns, 1u);
    for (int t = 0; t < voxel.targets; ++t) imageStore(grid, ivec3(p, t), uvec4(0u));
}
