// Solid voxelization (watertight meshes): every fragment XORs "everything behind me" into
// its column. A voxel ends up set when its centre has an odd number of surfaces in front of
// it along z, i.e. lies inside. Slice s is toggled by a surface at depth z when z < s + 0.5,
// which is the half-voxel correction: s >= floor(z + 0.5).
//! variant: TARGETS=1
//! variant: TARGETS=8
#include "voxel_params.glsl"

#ifndef TARGETS
#define TARGETS 1
#endif

in vec3 vVoxel;
layout(location = 0) out uvec4 slices[TARGETS];
// Bit 0 of layer 0: the parity of all crossings of the column, in front of, inside and behind
// the box (depth is clamped, not clipped), which is odd only where the mesh is open.
layout(binding = VOXEL_SCRATCH_IMAGE, r32ui) uniform uimage2DArray parity;

// Bits of 32-bit word `word` (slices 32 word .. 32 word + 31) at or behind slice s.
uint behind(int s, int word) {
    const int first = word * 32;
    if (s <= first) return 0xFFFFFFFFu;
    if (s >= first + 32) return 0u;
    return ~((1u << uint(s - first)) - 1u);
}

void main() {
    imageAtomicXor(parity, ivec3(ivec2(gl_FragCoord.xy), 0), 1u);
    // Clamped as float first: depth far outside the box has no defined int.
    const int s = int(clamp(floor(vVoxel.z + 0.5), 0.0, float(voxel.dims.z)));
    for (int t = 0; t < TARGETS; ++t)
        slices[t] = uvec4(behind(s, 4 * t), behind(s, 4 * t + 1), behind(s, 4 * t + 2), behind(s, 4 * t + 3));
}
