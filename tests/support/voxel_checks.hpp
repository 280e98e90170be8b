#pragma once
// Comparisons of dense voxel grids, CPU OR-reductions, and segment mixes for the voxel tests.
#include "obscura/voxelizer.hpp"

#include <cstddef>
#include <cstdint>
#include <optional>
#include <random>
#include <vector>

namespace obscura::test {

struct VoxelDiff {
    std::size_t expected = 0; //!< voxels set in the expected grid
    std::size_t actual = 0;   //!< voxels set in the actual grid
    std::size_t missing = 0;  //!< set in expected only
    std::size_t extra = 0;    //!< set in actual only
    std::size_t differing() const noexcept { return missing + extra; }
};

//! Voxel-by-voxel comparison; grids of different dims differ everywhere (missing = expected).
VoxelDiff compareVoxels(const DenseVoxels& actual, const DenseVoxels& expected);

//! Voxels set, in slices [zBegin, zEnd) (all when zEnd < 0).
std::size_t countSet(const DenseVoxels& grid, int zBegin = 0, int zEnd = -1);

//! Each output voxel ORs a block of factorXY x factorXY x factorZ input voxels; the z count
//! rounds up (a partial block ORs what it has).
DenseVoxels orReduce(const DenseVoxels& grid, int factorXY, int factorZ);
inline DenseVoxels orReduce(const DenseVoxels& grid, int factor) { return orReduce(grid, factor, factor); }

//! The parameter interval [t0, t1] (within [0, 1]) in which the segment from -> to lies in
//! the box [lo, hi] (double precision slab test), if any.
std::optional<std::pair<double, double>> segmentBoxInterval(const glm::dvec3& from, const glm::dvec3& to,
                                                            const glm::dvec3& lo, const glm::dvec3& hi);

//! Segments in voxel coordinates that exercise the traversal's special cases, in equal shares:
//! random (reaching outside the grid), axis-aligned (also along voxel faces and edges),
//! between lattice points (through voxel edges and corners), starting inside an occupied
//! voxel, zero-length (also on faces), and short (a few voxels, as ambient occlusion uses).
std::vector<VoxelSegment> segmentMix(const DenseVoxels& grid, std::size_t count, std::uint32_t seed);

} // namespace obscura::test
