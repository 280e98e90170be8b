// The surface pass's 32-slices-per-layer R32UI words into the RGBA32UI slicemap (128 per texel).
#include "voxel_params.glsl"

layout(local_size_x = VOXEL_WORKGROUP_2D, local_size_y = VOXEL_WORKGROUP_2D) in;
layout(binding = VOXEL_SCRATCH_IMAGE, r32ui) readonly uniform uimage2DArray words;
layout(binding = VOXEL_OUT_IMAGE, rgba32ui) writeonly uniform uimage2DArray grid;

void main() {
    const ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(p, voxel.dims.xy))) return;
    for (int t = 0; t < voxel.targets; ++t) {
        uvec4 texel;
        for (int c = 0; c < 4; ++c) texel[c] = imageLoad(words, ivec3(p, 4 * t + c)).r;
        imageStore(grid, ivec3(p, t), texel);
    }
}
