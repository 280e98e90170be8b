// The voxelizer's parameter block alone (passes that do not sample the grid).
#include "voxel_bindings.h"

layout(std140, binding = VOXEL_PARAMS_UBO_BINDING) uniform VoxelBlock {
    VoxelParams voxel;
};
