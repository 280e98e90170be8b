#include "voxel_checks.hpp"

#include <algorithm>
#include <stdexcept>

namespace obscura::test {

VoxelDiff compareVoxels(const DenseVoxels& actual, const DenseVoxels& expected) {
    VoxelDiff d;
    d.expected = countSet(expected);
    d.actual = countSet(actual);
    if (actual.dims != expected.dims) {
        d.missing = d.expected;
        d.extra = d.actual;
        return d;
    }
    for (std::size_t i = 0; i < actual.voxels.size(); ++i) {
        d.missing += expected.voxels[i] && !actual.voxels[i];
        d.extra += actual.voxels[i] && !expected.voxels[i];
    }
    return d;
}

std::size_t countSet(const DenseVoxels& grid, int zBegin, int zEnd) {
    if (zEnd < 0) zEnd = grid.dims.z;
    const std::size_t slice = static_cast<std::size_t>(grid.dims.x) * grid.dims.y;
    return static_cast<std::size_t>(std::count_if(grid.voxels.begin() + static_cast<std::ptrdiff_t>(slice * zBegin),
                                                  grid.voxels.begin() + static_cast<std::ptrdiff_t>(slice * zEnd),
                                                  [](std::uint8_t v) { return v != 0; }));
}

DenseVoxels orReduce(const DenseVoxels& grid, int factorXY, int factorZ) {
    DenseVoxels out;
    out.dims = {grid.dims.x / factorXY, grid.dims.y / factorXY, (grid.dims.z + factorZ - 1) / factorZ};
    out.voxels.assign(static_cast<std::size_t>(out.dims.x) * out.dims.y * out.dims.z, 0);
    for (int z = 0; z < grid.dims.z; ++z)
        for (int y = 0; y < out.dims.y * factorXY; ++y)
            for (int x = 0; x < out.dims.x * factorXY; ++x)
                if (grid.at(x, y, z))
                    out.voxels[(static_cast<std::size_t>(z / factorZ) * out.dims.y + y / factorXY) * out.dims.x +
                               x / factorXY] = 1;
    return out;
}

std::optional<std::pair<double, double>> segmentBoxInterval(const glm::dvec3& from, const glm::dvec3& to,
                                                            const glm::dvec3& lo, const glm::dvec3& hi) {
    double t0 = 0.0, t1 = 1.0;
    const glm::dvec3 d = to - from;
    for (int a = 0; a < 3; ++a) {
        if (d[a] == 0.0) {
            if (from[a] < lo[a] || from[a] > hi[a]) return std::nullopt;
            continue;
        }
        const double s0 = (lo[a] - from[a]) / d[a], s1 = (hi[a] - from[a]) / d[a];
        t0 = std::max(t0, std::min(s0, s1));
        t1 = std::min(t1, std::max(s0, s1));
    }
    if (t0 > t1) return std::nullopt;
    return std::pair{t0, t1};
}

std::vector<VoxelSegment> segmentMix(const DenseVoxels& grid, std::size_t count, std::uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    const glm::vec3 dims(grid.dims);
    std::vector<glm::ivec3> occupied;
    for (int z = 0; z < grid.dims.z; ++z)
        for (int y = 0; y < grid.dims.y; ++y)
            for (int x = 0; x < grid.dims.x; ++x)
                if (grid.at(x, y, z)) occupied.emplace_back(x, y, z);
    if (occupied.empty()) throw std::invalid_argument("segmentMix: the grid is empty");
    const auto inside = [&](float reach) { // uniform in the grid grown by `reach` of its size
        return glm::vec3(unit(rng), unit(rng), unit(rng)) * dims * (1.0f + 2.0f * reach) - reach * dims;
    };
    const auto lattice = [&] { // a lattice point: voxel corners
        return glm::floor(glm::vec3(unit(rng), unit(rng), unit(rng)) * (dims + 1.0f));
    };
    const auto axis = [&] { return static_cast<int>(unit(rng) * 3.0f) % 3; };
    std::vector<VoxelSegment> out;
    out.reserve(count);
    for (std::size_t i = 0; i < count; ++i) {
        VoxelSegment s;
        switch (i % 6) {
        case 0: s = {inside(0.1f), inside(0.1f)}; break;
        case 1: { // along one axis; half of them on voxel faces or edges
            s.from = inside(0.0f);
            if (unit(rng) < 0.5f) { // snap each coordinate to a voxel face with probability 1/2
                const glm::vec3 keep(unit(rng) < 0.5f, unit(rng) < 0.5f, unit(rng) < 0.5f);
                s.from = glm::floor(s.from) + keep * glm::fract(s.from);
            }
            s.to = s.from;
            const int a = axis();
            s.to[a] = unit(rng) * dims[a];
            break;
        }
        case 2: s = {lattice(), lattice()}; break;
        case 3: {
            const glm::ivec3 v = occupied[static_cast<std::size_t>(unit(rng) * static_cast<float>(occupied.size())) % occupied.size()];
            s.from = glm::vec3(v) + glm::vec3(unit(rng), unit(rng), unit(rng));
            s.to = inside(0.0f);
            break;
        }
        case 4: s.from = s.to = unit(rng) < 0.5f ? inside(0.0f) : lattice(); break;
        default: {
            s.from = inside(0.0f);
            const glm::vec3 d = glm::vec3(unit(rng), unit(rng), unit(rng)) * 2.0f - 1.0f;
            s.to = s.from + 4.0f * unit(rng) * d;
            break;
        }
        }
        out.push_back(s);
    }
    return out;
}

} // namespace obscura::test
