#pragma once
// Voxelizer: binary slicemap voxelization (Eisemann and Décoret) with OR-mipmaps, and
// visibility queries in voxel space.
//
// The grid has R x R columns of D = 128 k slices (R a power of two, k render targets). A
// column is stored in k RGBA32UI texels (128 one-bit voxels each) of a GL_TEXTURE_2D_ARRAY
// with k layers; slice z is bit z % 32 of component (z / 32) % 4 of layer z / 128.
//
// Surface mode (a voxel is set when a triangle touches it, its closed box): each triangle
// is rasterized along its dominant axis over its bounding box grown by a pixel, and every
// candidate voxel is tested exactly (separating axes) before an atomic OR. Holes from
// triangles seen edge-on or smaller than a voxel cannot happen. The test runs in float on
// triangle-relative coordinates with the box grown by g = 1e-5 + 2^-21 E voxel (E: the
// triangle's extent in voxels), so rounding may only add voxels the triangle misses by less
// than g: a conservative superset of the exact voxelization, which tests bound. A zero-area triangle (a segment or a point) sets the voxels it touches.
// Cost: one geometry pass plus a pack pass, and a 32-bit scratch grid.
//
// Solid mode (watertight meshes; a voxel is set when its centre is inside): one z pass with
// glLogicOp(GL_XOR) into k render targets, each fragment toggling its column from the slice
// behind it; the half-voxel shift of the method is corrected by toggling slices whose
// centre lies behind the surface. It equals the parity fill at the column centres up to the
// rasterizer's sub-pixel snapping of vertices (1/256 pixel on llvmpipe) and float depth
// interpolation. Columns with an odd number of crossings along their whole line, inside
// the box or not (the mesh is open there), are cleared and counted in
// VoxelGrid::openColumns; CPU meshes that are not closed (meshClosure) are named in a
// warning even where every column happens to cross them an even number of times.
//
// Voxels need not be cubes: each axis of the box is divided into its own number of voxels.
//
// Mipmaps (compute): the quadtree ORs 2x2 columns per level with all slices kept (mip levels
// of `texture`); the octree also ORs pairs of slices, so a level-L cell covers 2^L voxels
// along each axis (levels 1.. of `octree`, level L at mip L - 1).
//
// Queries in GLSL: module shaders include shaders/voxel/voxel_traversal.glsl
// (voxelOccupiedAtPoint, voxelTraceMarch, voxelTraceExact, voxelTraceHierarchical) and bind
// VoxelGrid::texture, ::octree and ::params at the points voxel_bindings.h names.
#include "obscura/camera.hpp"
#include "obscura/export.hpp"
#include "obscura/settings_table.hpp"
#include "obscura/scene.hpp"

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace obscura {

class Context;

enum class VoxelMode { Surface, Solid };

struct VoxelizerSettings {
    int resolution = 128; //!< R: voxels along x and y
    int targets = 1;      //!< k: D = 128 k slices along z
    VoxelMode mode = VoxelMode::Surface;
    //! Fit the box to the scene's bounds (CPU meshes), grown by `margin` of its largest
    //! extent on every side (an axis of zero extent gets that thickness too). Off: use
    //! boxMin and boxMax as given (boxMin < boxMax per axis).
    bool fitBox = true;
    float margin = 0.02f; //!< at least 1e-6 is used, so that geometry on the bounds stays inside
    glm::vec3 boxMin{0.0f};
    glm::vec3 boxMax{1.0f};
    //! Off (static scenes): re-voxelize only when the scene's meshes (their MeshData objects
    //! and transforms), the box or the settings change. Scenes with host MeshRefs are always
    //! re-voxelized (their buffers can change behind our back).
    bool dynamic = false;
    bool octree = true;
    //! The read-back waits for the GPU; per-frame users may turn it off (the columns are still
    //! cleared, openColumns stays 0).
    bool countOpenColumns = true;

    static const SettingsTable<VoxelizerSettings>& table(); //!< units and ranges (settings_table.hpp)
};

inline const SettingsTable<VoxelizerSettings>& VoxelizerSettings::table() {
    using S = VoxelizerSettings;
    using namespace settings;
    static const SettingsTable<S> rows = {
        number("resolution", &S::resolution, "voxels", "8|16|32|64|128|256|512|1024|2048", "R: columns along x and y"),
        number("targets", &S::targets, "render targets", "[1, 8]", "k: 128 slices each along z"),
        choice("mode", &S::mode, {{"surface", VoxelMode::Surface}, {"solid", VoxelMode::Solid}},
               "surfaces (OR) or solid interiors (XOR)"),
        flag("fitBox", &S::fitBox, "fit the box to the scene's bounds (else boxMin, boxMax)"),
        number("margin", &S::margin, "of the largest extent", "[0, 1]", "fitBox: the box grown by this on every side"),
        color("boxMin", &S::boxMin, "world units", "(-inf, inf)", "the box's lower corner (fitBox off)"),
        color("boxMax", &S::boxMax, "world units", "(-inf, inf)", "the box's upper corner (fitBox off)"),
        flag("dynamic", &S::dynamic, "re-voxelize on every call"),
        flag("octree", &S::octree, "build the octree mips (hierarchical traversal needs them)"),
        flag("countOpenColumns", &S::countOpenColumns, "solid mode: read the open-column count back"),
    };
    return rows;
}

//! The voxel grid, owned by the Voxelizer; valid until its next call.
struct VoxelGrid {
    unsigned texture = 0;  //!< GL_TEXTURE_2D_ARRAY, GL_RGBA32UI, R x R x k; mip levels = quadtree
    unsigned octree = 0;   //!< GL_TEXTURE_2D_ARRAY, GL_RGBA32UI; octree level L at mip L - 1 (0 if off)
    glm::ivec3 dims{0};    //!< (R, R, D) voxels
    int targets = 0;       //!< k
    int levels = 0;        //!< octree levels above level 0 (log2 R when built, else 0)
    glm::dvec3 boxMin{0.0}, boxMax{0.0}; //!< world units
    glm::dmat4 worldToVoxel{1.0}; //!< world to voxel coordinates in [0, dims]
    unsigned params = 0;   //!< GL uniform buffer holding the VoxelParams block (voxel_bindings.h)
    std::size_t openColumns = 0;  //!< solid mode: columns cleared because the mesh is open there
    std::uint64_t version = 0;    //!< increases whenever the grid is rebuilt
};

enum class VoxelTraversal {
    March,        //!< (a) jittered ray marching, `marchSteps` occupancy samples (approximate)
    Exact,        //!< (b) every level-0 voxel along the segment (3D DDA, exact)
    Hierarchical, //!< (c) the same first hit as (b), skipping empty octree cells (exact, fewer fetches)
};

namespace settings {

//! The traversal row of the modules that trace through a grid.
template <class S>
Setting<S> voxelTraversalRow(std::string field, VoxelTraversal S::*member, std::string doc) {
    return choice(std::move(field), member,
                  {{"march", VoxelTraversal::March}, {"exact", VoxelTraversal::Exact},
                   {"hierarchical", VoxelTraversal::Hierarchical}},
                  std::move(doc));
}

} // namespace settings

struct TraversalSettings {
    VoxelTraversal method = VoxelTraversal::Hierarchical;
    int marchSteps = 64;
    std::uint32_t seed = 1;

    static const SettingsTable<TraversalSettings>& table(); //!< units and ranges (settings_table.hpp)
};

inline const SettingsTable<TraversalSettings>& TraversalSettings::table() {
    using S = TraversalSettings;
    using namespace settings;
    static const SettingsTable<S> rows = {
        voxelTraversalRow("method", &S::method, "march (approximate), exact 3D DDA, or hierarchical (exact, fewer fetches)"),
        number("marchSteps", &S::marchSteps, "samples", "[1, 4096]", "March: occupancy samples per segment"),
        number("seed", &S::seed, "", "[0, 4294967295]", "March: the per-segment jitter's seed"),
    };
    return rows;
}

//! A segment in voxel coordinates ([0, dims] per axis; VoxelGrid::worldToVoxel maps world
//! points there). Parts outside the grid are empty space. Endpoints are accepted within
//! 2^24 voxels of the origin; NaN, Inf or farther give a miss.
struct VoxelSegment {
    glm::vec3 from{0.0f}, to{0.0f};
};

struct VoxelHit {
    bool hit = false;
    //! Segment parameter in [0, 1] of the hit: for Exact and Hierarchical the entry into the
    //! first occupied voxel, for March the sample that found it; 1 for a miss.
    float t = 1.0f;
    glm::ivec3 voxel{-1};    //!< that voxel (level 0)
    std::uint32_t fetches = 0; //!< occupancy tests made (texel fetches)
};

//! The grid on the CPU: one byte per voxel (0 or 1), x fastest, then y, then z.
struct DenseVoxels {
    glm::ivec3 dims{0};
    std::vector<std::uint8_t> voxels;
    std::uint8_t at(int x, int y, int z) const {
        return voxels[(static_cast<std::size_t>(z) * dims.y + y) * dims.x + x];
    }
};

//! Edge counts of a mesh with its vertices welded by exact position: a watertight (closed,
//! manifold) surface has every edge on exactly two triangles. Zero-area triangles are
//! ignored. Solid voxelization checks every CPU mesh this way (once per MeshData).
struct MeshClosure {
    std::size_t edges = 0;
    std::size_t boundaryEdges = 0;    //!< on one triangle
    std::size_t nonManifoldEdges = 0; //!< on three or more
    bool watertight() const noexcept { return edges > 0 && boundaryEdges == 0 && nonManifoldEdges == 0; }
};
OBSCURA_API MeshClosure meshClosure(const MeshData& mesh);

class OBSCURA_API Voxelizer {
public:
    explicit Voxelizer(Context& context);
    ~Voxelizer();

    //! Voxelizes the scene's meshes and mesh references (passes "voxel.surface" or
    //! "voxel.solid", "voxel.mips"). Throws Error{InvalidArgument} for settings outside their
    //! ranges, an invalid scene (validateScene: NaN vertices among others), or an empty
    //! scene with fitBox.
    const VoxelGrid& voxelize(const Scene& scene, const VoxelizerSettings& settings);

    //! Traces segments through the current grid on the GPU (pass "voxel.trace"). NaN or Inf
    //! endpoints give a miss. A zero-length segment tests the voxel holding its point.
    std::vector<VoxelHit> trace(const std::vector<VoxelSegment>& segments, const TraversalSettings& settings);
    //! Point occupancy (voxel coordinates) through the GLSL voxelOccupiedAtPoint: 1 where the
    //! voxel holding the point is set (a point on a face belongs to the voxel above it);
    //! outside the grid, NaN or Inf: 0 (pass "voxel.trace").
    std::vector<std::uint8_t> occupancy(const std::vector<glm::vec3>& points);

    //! Reads the grid back (level 0), or an octree level (1..levels) at its own resolution.
    DenseVoxels download(int octreeLevel = 0);
    //! Reads quadtree level L (R/2^L x R/2^L columns of all D slices) back.
    DenseVoxels downloadQuadtree(int level);

    const VoxelGrid& grid() const noexcept;
    //! Messages about the last voxelization (e.g. open meshes in solid mode).
    const std::vector<std::string>& warnings() const noexcept;
    std::size_t memoryBytes() const;

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

} // namespace obscura
