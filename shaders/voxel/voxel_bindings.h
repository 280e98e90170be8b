// Voxelizer and voxel visibility: binding points, locations and the parameter block,
// shared by src/voxel/*.cpp and shaders/voxel/*.glsl.
#ifndef OBSCURA_VOXEL_BINDINGS_H
#define OBSCURA_VOXEL_BINDINGS_H

#include "../common/bindings_preamble.h"

OBSCURA_SHADER_BEGIN

#define VOXEL_SLICES_PER_TARGET 128
#define VOXEL_MAX_TARGETS 8
// Segments are traversed in fixed point, 2^12 steps per voxel (see voxel_traversal.glsl).
#define VOXEL_FIXED_SHIFT 12

#define VOXEL_PARAMS_UBO_BINDING 1
#define VOXEL_GRID_UNIT 3     // usampler2DArray: level 0 and the quadtree mips
#define VOXEL_OCTREE_UNIT 4   // usampler2DArray: octree level L at mip L - 1
#define VOXEL_SCRATCH_IMAGE 1 // r32ui 2D array, one layer per 32 slices (surface voxelization)
#define VOXEL_OUT_IMAGE 2
#define VOXEL_IN_IMAGE 3
#define VOXEL_SEGMENTS_SSBO 1
#define VOXEL_RESULTS_SSBO 2
#define VOXEL_COUNTER_SSBO 3

#define VOXEL_LOC_MODEL_TO_VOXEL 0 // dmat4
#define VOXEL_LOC_LEVEL 1
#define VOXEL_LOC_METHOD 2
#define VOXEL_LOC_STEPS 3
#define VOXEL_LOC_SEED 4
#define VOXEL_LOC_COUNT 5
#define VOXEL_LOC_FIRST 6 // the first query of this dispatch (batches larger than one dispatch)

#define VOXEL_METHOD_MARCH 0
#define VOXEL_METHOD_EXACT 1
#define VOXEL_METHOD_HIERARCHICAL 2
#define VOXEL_METHOD_OCCUPANCY 3 // point queries: `from` only

#define VOXEL_WORKGROUP_2D 8
#define VOXEL_WORKGROUP_1D 64

struct VoxelParams {
    ivec3 dims;       // R, R, D slices
    int octreeLevels; // above level 0 (0: none)
    int targets;      // render targets k
    int surfaceViewport; // the surface pass's viewport side, pixels
    int pad0;
    int pad1;
};

#ifdef __cplusplus
static_assert(sizeof(VoxelParams) == 32, "VoxelParams must match std140");
#endif

OBSCURA_SHADER_END

#endif
