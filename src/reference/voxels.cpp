// CPU voxelizations, the ground truth of the GPU voxelizer.
#include "obscura/error.hpp"
#include "obscura/reference.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <string>

namespace obscura::reference {
namespace {

using Triangle = std::array<glm::dvec3, 3>;

// Every triangle of the scene's CPU meshes in voxel coordinates; zero-area ones (segments
// and points) only when asked for.
template <typename F>
void forEachTriangle(const Scene& scene, const glm::dmat4& worldToVoxel, bool withZeroArea, F&& f) {
    for (const Mesh& m : scene.meshes) {
        const glm::dmat4 toVoxel = worldToVoxel * glm::dmat4(m.model);
        const MeshData& d = *m.data;
        const std::size_t count = d.indices.empty() ? d.positions.size() : d.indices.size();
        for (std::size_t i = 0; i + 2 < count; i += 3) {
            Triangle t;
            for (int k = 0; k < 3; ++k) {
                const std::size_t v = d.indices.empty() ? i + static_cast<std::size_t>(k) : d.indices[i + static_cast<std::size_t>(k)];
                t[static_cast<std::size_t>(k)] = glm::dvec3(toVoxel * glm::dvec4(glm::dvec3(d.positions[v]), 1.0));
            }
            if (!withZeroArea && glm::length(glm::cross(t[1] - t[0], t[2] - t[0])) == 0.0) continue;
            f(t);
        }
    }
}

bool separated(const glm::dvec3& axis, const Triangle& v, double halfSize) {
    const double p0 = glm::dot(axis, v[0]), p1 = glm::dot(axis, v[1]), p2 = glm::dot(axis, v[2]);
    const double r = halfSize * (std::abs(axis.x) + std::abs(axis.y) + std::abs(axis.z));
    return std::min({p0, p1, p2}) > r || std::max({p0, p1, p2}) < -r;
}

// Akenine-Moeller's triangle/box overlap for the unit voxel at `cell` (closed boxes) grown
// by `grow` on every side.
bool overlaps(const Triangle& t, const glm::dvec3& cell, double grow) {
    const glm::dvec3 c = cell + 0.5;
    const double h = 0.5 + grow;
    const Triangle v = {t[0] - c, t[1] - c, t[2] - c};
    for (int a = 0; a < 3; ++a)
        if (std::min({v[0][a], v[1][a], v[2][a]}) > h || std::max({v[0][a], v[1][a], v[2][a]}) < -h) return false;
    const glm::dvec3 e[3] = {v[1] - v[0], v[2] - v[1], v[0] - v[2]};
    if (separated(glm::cross(e[0], e[1]), v, h)) return false;
    for (int a = 0; a < 3; ++a) {
        glm::dvec3 axis(0.0);
        axis[a] = 1.0;
        for (const auto& edge : e)
            if (separated(glm::cross(axis, edge), v, h)) return false;
    }
    return true;
}

// Whether point p is on the inner side of the counter-clockwise edge a -> b, with `w` its
// edge function (twice the signed area of a, b, p). Points on the edge belong to one side
// only (a top-left rule): of two triangles sharing the edge in opposite directions exactly
// one owns them, so a column through a shared edge counts one crossing, not two.
bool ownsPoint(const glm::dvec2& a, const glm::dvec2& b, const glm::dvec2& p, double& w) {
    w = (b.x - a.x) * (p.y - a.y) - (b.y - a.y) * (p.x - a.x);
    if (w != 0.0) return w > 0.0;
    const glm::dvec2 e = b - a;
    return e.y < 0.0 || (e.y == 0.0 && e.x > 0.0);
}

// floor(v) as an index, clamped to [-1, n] in double first (coordinates far outside the
// grid have no int).
int cellIndex(double v, int n) { return static_cast<int>(std::clamp(std::floor(v), -1.0, static_cast<double>(n))); }

DenseVoxels empty(const VoxelGrid& grid) {
    DenseVoxels out;
    out.dims = grid.dims;
    out.voxels.assign(static_cast<std::size_t>(grid.dims.x) * grid.dims.y * grid.dims.z, 0);
    return out;
}

void requireLayout(const VoxelGrid& grid) {
    if (glm::any(glm::lessThan(grid.dims, glm::ivec3(1))))
        throw Error(ErrorCode::InvalidArgument, "CPU voxelization: the grid layout has no voxels");
}

} // namespace

DenseVoxels voxelizeSurface(const Scene& scene, const VoxelGrid& grid, double grow) {
    requireLayout(grid);
    if (!(grow >= 0.0 && grow < 0.5))
        throw Error(ErrorCode::InvalidArgument, "voxelizeSurface: grow must be in [0, 0.5) voxel, got " + std::to_string(grow));
    validateScene(scene);
    DenseVoxels out = empty(grid);
    forEachTriangle(scene, grid.worldToVoxel, true, [&](const Triangle& t) {
        glm::ivec3 lo, hi;
        for (int a = 0; a < 3; ++a) {
            lo[a] = std::max(0, cellIndex(std::min({t[0][a], t[1][a], t[2][a]}) - grow, grid.dims[a]) - 1);
            hi[a] = std::min(grid.dims[a] - 1, cellIndex(std::max({t[0][a], t[1][a], t[2][a]}) + grow, grid.dims[a]) + 1);
        }
        for (int z = lo.z; z <= hi.z; ++z)
            for (int y = lo.y; y <= hi.y; ++y)
                for (int x = lo.x; x <= hi.x; ++x) {
                    const std::size_t i = (static_cast<std::size_t>(z) * grid.dims.y + y) * grid.dims.x + x;
                    if (!out.voxels[i] && overlaps(t, glm::dvec3(x, y, z), grow)) out.voxels[i] = 1;
                }
    });
    return out;
}

DenseVoxels voxelizeSolid(const Scene& scene, const VoxelGrid& grid) {
    requireLayout(grid);
    validateScene(scene);
    DenseVoxels out = empty(grid);
    // For each column, the depths at which surfaces cross its centre line.
    std::vector<std::vector<double>> crossings(static_cast<std::size_t>(grid.dims.x) * grid.dims.y);
    forEachTriangle(scene, grid.worldToVoxel, false, [&](const Triangle& t) {
        double area = (t[1].x - t[0].x) * (t[2].y - t[0].y) - (t[2].x - t[0].x) * (t[1].y - t[0].y);
        if (area == 0.0) return; // seen edge-on from z: no column crosses it
        Triangle v = t;
        if (area < 0.0) { // counter-clockwise, so that shared edges run in opposite directions
            std::swap(v[1], v[2]);
            area = -area;
        }
        const int x0 = std::max(0, cellIndex(std::min({v[0].x, v[1].x, v[2].x}) - 0.5, grid.dims.x));
        const int x1 = std::min(grid.dims.x - 1, cellIndex(std::max({v[0].x, v[1].x, v[2].x}) + 1.0, grid.dims.x));
        const int y0 = std::max(0, cellIndex(std::min({v[0].y, v[1].y, v[2].y}) - 0.5, grid.dims.y));
        const int y1 = std::min(grid.dims.y - 1, cellIndex(std::max({v[0].y, v[1].y, v[2].y}) + 1.0, grid.dims.y));
        for (int y = y0; y <= y1; ++y)
            for (int x = x0; x <= x1; ++x) {
                const glm::dvec2 p(x + 0.5, y + 0.5);
                double w[3];
                bool inside = true;
                for (int k = 0; k < 3 && inside; ++k)
                    inside = ownsPoint(glm::dvec2(v[(k + 1) % 3]), glm::dvec2(v[(k + 2) % 3]), p, w[k]);
                if (!inside) continue;
                const double z = (w[0] * v[0].z + w[1] * v[1].z + w[2] * v[2].z) / area;
                crossings[static_cast<std::size_t>(y) * grid.dims.x + x].push_back(z);
            }
    });
    for (int y = 0; y < grid.dims.y; ++y)
        for (int x = 0; x < grid.dims.x; ++x) {
            const auto& zs = crossings[static_cast<std::size_t>(y) * grid.dims.x + x];
            for (int z = 0; z < grid.dims.z; ++z) {
                std::size_t below = 0;
                for (double c : zs) below += c < z + 0.5;
                out.voxels[(static_cast<std::size_t>(z) * grid.dims.y + y) * grid.dims.x + x] = below % 2;
            }
        }
    return out;
}

} // namespace obscura::reference
