#include "voxel_bench.hpp"

#include "obscura/assets.hpp"
#include "obscura/error.hpp"
#include "obscura/profiler.hpp"
#include "obscura/voxelizer.hpp"

#include <glm/gtc/matrix_transform.hpp>

#include <cmath>
#include <cstdio>
#include <random>

namespace obscura::cli {
namespace {

std::size_t triangleCount(const Scene& scene) {
    std::size_t n = 0;
    for (const Mesh& m : scene.meshes) n += (m.data->indices.empty() ? m.data->positions.size() : m.data->indices.size()) / 3;
    return n;
}

// Copies of the scene side by side (sharing their mesh data) on a grid of n x n x n slots,
// as many as bring the triangle count nearest to `triangles`.
Scene replicated(const Scene& scene, std::size_t triangles, int& copies) {
    const std::size_t one = triangleCount(scene);
    if (one == 0) throw Error(ErrorCode::InvalidArgument, "bench: the voxelization scene has no triangles");
    copies = std::max(1, static_cast<int>(std::lround(static_cast<double>(triangles) / static_cast<double>(one))));
    int perAxis = 1;
    while (perAxis * perAxis * perAxis < copies) ++perAxis;
    const Bounds b = sceneBounds(scene);
    const glm::vec3 step = 1.1f * (b.max - b.min);
    Scene out = scene;
    out.meshes.clear();
    for (int i = 0; i < copies; ++i) {
        const glm::vec3 slot(i % perAxis, (i / perAxis) % perAxis, i / (perAxis * perAxis));
        for (Mesh m : scene.meshes) {
            m.model = glm::translate(glm::mat4(1.0f), step * slot) * m.model;
            out.meshes.push_back(m);
        }
    }
    return out;
}

nlohmann::ordered_json passTimes(Profiler& profiler, double& total) {
    nlohmann::ordered_json passes = nlohmann::ordered_json::array();
    total = 0.0;
    for (const PassStatistics& s : profiler.statistics(/*wait=*/true)) {
        total += s.medianMs;
        passes.push_back({{"pass", s.name}, {"median_ms", s.medianMs}, {"min_ms", s.minMs}, {"max_ms", s.maxMs},
                          {"samples", s.samples}});
    }
    return passes;
}

nlohmann::ordered_json benchVoxelization(Context& ctx, const VoxelBenchOptions& o) {
    nlohmann::ordered_json rows = nlohmann::ordered_json::array();
    const assets::LoadedScene loaded = assets::loadScene(o.scene);
    int copies = 1;
    const Scene scene = replicated(loaded.scene, o.triangles, copies);
    const std::size_t triangles = triangleCount(scene);
    std::printf("voxelization: %d copies of %s, %zu triangles in %zu meshes\n", copies, loaded.name.c_str(), triangles,
                scene.meshes.size());
    Voxelizer voxelizer(ctx);
    for (VoxelMode mode : {VoxelMode::Surface, VoxelMode::Solid})
        for (int resolution : o.resolutions)
            for (int targets : o.targets) {
                VoxelizerSettings s;
                s.resolution = resolution;
                s.targets = targets;
                s.mode = mode;
                s.dynamic = true;
                voxelizer.voxelize(scene, s); // warm-up: compilation, allocation, mesh upload
                ctx.profiler().reset();
                for (int i = 0; i < o.frames; ++i) voxelizer.voxelize(scene, s);
                double total = 0.0;
                nlohmann::ordered_json passes = passTimes(ctx.profiler(), total);
                const char* modeName = mode == VoxelMode::Surface ? "surface" : "solid";
                rows.push_back({{"scene", loaded.name}, {"copies", copies}, {"triangles", triangles},
                                {"mode", modeName}, {"resolution", resolution}, {"slices", 128 * targets},
                                {"targets", targets}, {"ms", total}, {"clock", toString(ctx.profiler().clock())},
                                {"frames", o.frames}, {"memory_bytes", voxelizer.memoryBytes()},
                                {"open_columns", voxelizer.grid().openColumns}, {"passes", passes},
                                {"renderer", ctx.info().renderer}});
                std::printf("  %-7s %4d x %4d x %4d (%d targets): %9.2f ms (%s)\n", modeName, resolution, resolution,
                            128 * targets, targets, total, toString(ctx.profiler().clock()));
            }
    return rows;
}

// Segments between points drawn uniformly in the grid, of any length ("random") or of at
// most 16 voxels ("short", like ambient occlusion rays).
std::vector<VoxelSegment> benchSegments(const glm::ivec3& dims, std::size_t count, bool shortOnes) {
    std::mt19937 rng(42);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    const glm::vec3 size(dims);
    std::vector<VoxelSegment> out(count);
    for (VoxelSegment& s : out) {
        s.from = glm::vec3(u(rng), u(rng), u(rng)) * size;
        if (!shortOnes) {
            s.to = glm::vec3(u(rng), u(rng), u(rng)) * size;
        } else {
            glm::vec3 d(u(rng) * 2.0f - 1.0f, u(rng) * 2.0f - 1.0f, u(rng) * 2.0f - 1.0f);
            s.to = s.from + 16.0f * u(rng) * d / std::max(glm::length(d), 1e-3f);
        }
    }
    return out;
}

nlohmann::ordered_json benchTraversal(Context& ctx, const VoxelBenchOptions& o) {
    nlohmann::ordered_json rows = nlohmann::ordered_json::array();
    Voxelizer voxelizer(ctx);
    for (const std::string& name : o.traversalScenes) {
        const assets::LoadedScene loaded = assets::loadScene(name);
        VoxelizerSettings s;
        s.resolution = o.traversalResolution;
        const VoxelGrid& grid = voxelizer.voxelize(loaded.scene, s);
        for (bool shortOnes : {false, true}) {
            const auto segments = benchSegments(grid.dims, o.segments, shortOnes);
            TraversalSettings exactSettings;
            exactSettings.method = VoxelTraversal::Exact;
            const std::vector<VoxelHit> exact = voxelizer.trace(segments, exactSettings);
            for (VoxelTraversal method : {VoxelTraversal::March, VoxelTraversal::Exact, VoxelTraversal::Hierarchical}) {
                TraversalSettings t;
                t.method = method;
                t.marchSteps = o.marchSteps;
                std::vector<VoxelHit> hits = voxelizer.trace(segments, t); // warm-up
                ctx.profiler().reset();
                for (int i = 0; i < o.frames; ++i) hits = voxelizer.trace(segments, t);
                double ms = 0.0;
                passTimes(ctx.profiler(), ms);
                double fetches = 0.0;
                std::size_t agree = 0, hitCount = 0;
                for (std::size_t i = 0; i < hits.size(); ++i) {
                    fetches += hits[i].fetches;
                    agree += hits[i].hit == exact[i].hit;
                    hitCount += hits[i].hit;
                }
                const char* methodName = method == VoxelTraversal::March   ? "march"
                                         : method == VoxelTraversal::Exact ? "exact"
                                                                           : "hierarchical";
                const double n = static_cast<double>(hits.size());
                rows.push_back({{"scene", loaded.name}, {"resolution", grid.dims.x}, {"slices", grid.dims.z},
                                {"segments", shortOnes ? "short" : "random"}, {"count", hits.size()},
                                {"method", methodName}, {"march_steps", method == VoxelTraversal::March ? o.marchSteps : 0},
                                {"ms", ms}, {"segments_per_second", n / (ms * 1e-3)}, {"mean_fetches", fetches / n},
                                {"hit_fraction", static_cast<double>(hitCount) / n},
                                {"agrees_with_exact", static_cast<double>(agree) / n},
                                {"clock", toString(ctx.profiler().clock())}, {"frames", o.frames},
                                {"renderer", ctx.info().renderer}});
                std::printf("  %-16s %-6s %-12s %9.2f ms  %8.3g segments/s  %7.2f fetches  %.4f agree with exact\n",
                            loaded.name.c_str(), shortOnes ? "short" : "random", methodName, ms, n / (ms * 1e-3),
                            fetches / n, static_cast<double>(agree) / n);
            }
        }
    }
    return rows;
}

} // namespace

nlohmann::ordered_json benchVoxelizer(Context& ctx, const VoxelBenchOptions& o) {
    if (o.frames < 20) throw Error(ErrorCode::Parse, "--frames must be >= 20 (the median of at least 20 warm frames)");
    return {{"voxelization", benchVoxelization(ctx, o)}, {"traversal", benchTraversal(ctx, o)}};
}

} // namespace obscura::cli
