// Watertightness of a mesh by edge counts (for solid voxelization's warnings).
#include "obscura/error.hpp"
#include "obscura/voxelizer.hpp"

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstring>
#include <string>
#include <unordered_map>

namespace obscura {
namespace {

struct PositionHash {
    std::size_t operator()(const glm::vec3& p) const noexcept {
        std::uint32_t bits[3];
        std::memcpy(bits, &p, sizeof bits);
        return (static_cast<std::size_t>(bits[0]) * 73856093u) ^ (static_cast<std::size_t>(bits[1]) * 19349663u) ^
               (static_cast<std::size_t>(bits[2]) * 83492791u);
    }
};

} // namespace

MeshClosure meshClosure(const MeshData& mesh) {
    // Welded vertex ids (equal positions share one; +0 and -0 compare equal and hash alike
    // after the normalisation below), then each undirected edge's triangle count.
    std::unordered_map<glm::vec3, std::uint32_t, PositionHash> ids;
    const auto id = [&](glm::vec3 p) {
        for (int a = 0; a < 3; ++a)
            if (p[a] == 0.0f) p[a] = 0.0f;
        return ids.emplace(p, static_cast<std::uint32_t>(ids.size())).first->second;
    };
    std::unordered_map<std::uint64_t, std::uint32_t> edges;
    const std::size_t count = mesh.indices.empty() ? mesh.positions.size() : mesh.indices.size();
    for (std::uint32_t index : mesh.indices)
        if (index >= mesh.positions.size())
            throw Error(ErrorCode::InvalidArgument, "meshClosure: index " + std::to_string(index) + " is beyond the " +
                                                        std::to_string(mesh.positions.size()) + " positions");
    for (std::size_t i = 0; i + 2 < count; i += 3) {
        std::array<glm::vec3, 3> p;
        for (std::size_t k = 0; k < 3; ++k) p[k] = mesh.positions[mesh.indices.empty() ? i + k : mesh.indices[i + k]];
        if (glm::cross(p[1] - p[0], p[2] - p[0]) == glm::vec3(0.0f)) continue;
        const std::uint32_t v[3] = {id(p[0]), id(p[1]), id(p[2])};
        for (int k = 0; k < 3; ++k) {
            const std::uint64_t lo = std::min(v[k], v[(k + 1) % 3]), hi = std::max(v[k], v[(k + 1) % 3]);
            ++edges[lo << 32 | hi];
        }
    }
    MeshClosure c;
    c.edges = edges.size();
    for (const auto& e : edges) {
        c.boundaryEdges += e.second == 1;
        c.nonManifoldEdges += e.second > 2;
    }
    return c;
}

} // namespace obscura
