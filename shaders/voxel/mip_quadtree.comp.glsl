// Quadtree mip: level L ORs 2x2 columns of level L - 1, all slices kept (the source thesis's
// OR-mipmap of the slicemap).
#include "voxel_params.glsl"

layout(local_size_x = VOXEL_WORKGROUP_2D, local_size_y = VOXEL_WORKGROUP_2D) in;
layout(binding = VOXEL_IN_IMAGE, rgba32ui) readonly uniform uimage2DArray finer;
layout(binding = VOXEL_OUT_IMAGE, rgba32ui) writeonly uniform uimage2DArray coarser;
layout(location = VOXEL_LOC_LEVEL) uniform int level;

void main() {
    const ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(p, voxel.dims.xy >> level))) return;
    for (int t = 0; t < voxel.targets; ++t) {
        uvec4 bits = uvec4(0u);
        for (int i = 0; i < 4; ++i) bits |= imageLoad(finer, ivec3(2 * p + ivec2(i & 1, i >> 1), t));
        imageStore(coarser, ivec3(p, t), bits);
    }
}
