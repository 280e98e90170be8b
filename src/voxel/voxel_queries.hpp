#pragma once
// What the modules that query the voxel grid from their shaders share (voxel AO, hybrid
// GI): checks, the traversal permutation, the bindings and the view-to-voxel transform.
#include "core/gl.hpp"
#include "obscura/camera.hpp"
#include "obscura/voxelizer.hpp"

#include <string>

namespace obscura::detail {

struct ContextImpl;

//! Throws Error{InvalidArgument} unless `grid` is a built grid the traversal can use
//! (Hierarchical needs the octree). `owner` names the setting, e.g. "AmbientOcclusionSettings".
void requireVoxelGrid(const VoxelGrid* grid, VoxelTraversal traversal, const std::string& owner);
//! VOXEL_METHOD_* of the traversal (the TRAVERSAL permutation of the integrator shaders).
int voxelTraversalCode(VoxelTraversal traversal);
//! Throws Error{InvalidArgument} for a traversal outside its enumerators; `what` names the field.
void requireTraversal(VoxelTraversal traversal, const std::string& what);
//! Binds the grid's parameter block and textures where voxel_traversal.glsl reads them.
void bindVoxelGrid(ContextImpl& ctx, const VoxelGrid& grid);
//! A voxel's diagonal with the largest side, world units: rays start this far off a surface
//! so that its own voxels are not taken for occluders.
double voxelDiagonal(const VoxelGrid& grid);
//! View space of the camera to voxel coordinates, composed in double.
glm::mat4 viewToVoxel(const VoxelGrid& grid, const Camera& camera);

} // namespace obscura::detail
