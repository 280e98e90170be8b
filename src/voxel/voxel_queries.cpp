#include "voxel/voxel_queries.hpp"

#include "core/context_impl.hpp"
#include "core/validate.hpp"
#include "obscura/error.hpp"
#include "shaders/voxel/voxel_bindings.h"

#include <algorithm>
#include <cmath>

namespace obscura::detail {

void requireVoxelGrid(const VoxelGrid* grid, VoxelTraversal traversal, const std::string& owner) {
    requireTraversal(traversal, owner + "::voxelTraversal");
    if (!grid || grid->texture == 0)
        throw Error(ErrorCode::InvalidArgument, "the voxel-space method needs " + owner +
                                                    "::voxels, a grid from Voxelizer::voxelize of the same scene");
    if (traversal == VoxelTraversal::Hierarchical && grid->octree == 0)
        throw Error(ErrorCode::InvalidArgument, "hierarchical voxel traversal needs the grid's octree (VoxelizerSettings::octree)");
}

void requireTraversal(VoxelTraversal traversal, const std::string& what) {
    requireEnumerator(traversal, {VoxelTraversal::March, VoxelTraversal::Exact, VoxelTraversal::Hierarchical}, what);
}

int voxelTraversalCode(VoxelTraversal t) {
    return t == VoxelTraversal::March ? VOXEL_METHOD_MARCH : t == VoxelTraversal::Exact ? VOXEL_METHOD_EXACT
                                                                                         : VOXEL_METHOD_HIERARCHICAL;
}

void bindVoxelGrid(ContextImpl& ctx, const VoxelGrid& grid) {
    ctx.state.bindUniformBuffer(ctx, VOXEL_PARAMS_UBO_BINDING, grid.params);
    ctx.state.bindTexture(ctx, VOXEL_GRID_UNIT, grid.texture);
    ctx.state.bindSampler(ctx, VOXEL_GRID_UNIT, ctx.nearestClampSampler());
    if (grid.octree) {
        ctx.state.bindTexture(ctx, VOXEL_OCTREE_UNIT, grid.octree);
        ctx.state.bindSampler(ctx, VOXEL_OCTREE_UNIT, ctx.nearestClampSampler());
    }
}

double voxelDiagonal(const VoxelGrid& grid) {
    const glm::dvec3 size = (grid.boxMax - grid.boxMin) / glm::dvec3(grid.dims);
    return std::sqrt(3.0) * std::max({size.x, size.y, size.z});
}

glm::mat4 viewToVoxel(const VoxelGrid& grid, const Camera& camera) {
    return glm::mat4(grid.worldToVoxel * glm::inverse(glm::dmat4(camera.view)));
}

} // namespace obscura::detail
