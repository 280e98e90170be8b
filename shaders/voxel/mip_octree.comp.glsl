// Octree mip: level L ORs 2x2 columns of level L - 1 and then pairs of slices, so a cell
// covers 2^L voxels along every axis. Column bit j of level L = bits 2j | 2j + 1 below.
#include "voxel_params.glsl"

layout(local_size_x = VOXEL_WORKGROUP_2D, local_size_y = VOXEL_WORKGROUP_2D) in;
layout(binding = VOXEL_IN_IMAGE, rgba32ui) readonly uniform uimage2DArray finer;
layout(binding = VOXEL_OUT_IMAGE, rgba32ui) writeonly uniform uimage2DArray coarser;
layout(location = VOXEL_LOC_LEVEL) uniform int level;

// The even bits of x (after OR-ing each pair into it) packed into the low 16 bits.
uint compactPairs(uint x) {
    x = (x | (x >> 1)) & 0x55555555u;
    x = (x | (x >> 1)) & 0x33333333u;
    x = (x | (x >> 2)) & 0x0F0F0F0Fu;
    x = (x | (x >> 4)) & 0x00FF00FFu;
    x = (x | (x >> 8)) & 0x0000FFFFu;
    return x;
}

// Word w (32 slices) of the finer column, OR-ed over the 2x2 children.
uint finerWord(ivec2 p, int w) {
    uint bits = 0u;
    for (int i = 0; i < 4; ++i) bits |= imageLoad(finer, ivec3(2 * p + ivec2(i & 1, i >> 1), w >> 2))[w & 3];
    return bits;
}

void main() {
    const ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(p, voxel.dims.xy >> level))) return;
    // Words holding the finer column: ceil(ceil(D / 2^(L-1)) / 32).
    const int finerSlices = (voxel.dims.z + (1 << (level - 1)) - 1) >> (level - 1);
    const int finerWords = (finerSlices + 31) / 32;
    for (int t = 0; t < voxel.targets; ++t) {
        uvec4 texel = uvec4(0u);
        for (int c = 0; c < 4; ++c) {
            const int w = 4 * t + c, lo = 2 * w, hi = 2 * w + 1;
            const uint a = lo < finerWords ? finerWord(p, lo) : 0u;
            const uint b = hi < finerWords ? finerWord(p, hi) : 0u;
            texel[c] = compactPairs(a) | (compactPairs(b) << 16);
        }
        imageStore(coarser, ivec3(p, t), texel);
    }
}
