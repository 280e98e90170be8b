#pragma once
// The voxelizer's part of `obscura bench`: voxelization time against grid size and render
// targets on a scene of about a million triangles, and traversal throughput and texel
// fetches of marching (a), exact DDA (b) and hierarchical traversal (c).
#include "obscura/context.hpp"

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace obscura::cli {

struct VoxelBenchOptions {
    std::string scene;                   //!< voxelization: copies of it, about `triangles` in all
    std::size_t triangles = 1000000;     //!< the copies' count is the nearest to this
    std::vector<int> resolutions{128, 512};
    std::vector<int> targets{1, 4, 8};
    std::vector<std::string> traversalScenes{"cornell"};
    int traversalResolution = 128;
    std::size_t segments = 1 << 20;      //!< per traversal measurement
    int marchSteps = 64;                 //!< (a)'s samples per segment
    int frames = 20;                     //!< timed repetitions (median), after a warm-up
};

//! {"voxelization": [...], "traversal": [...]} rows (keys in CSV column order); also printed
//! as they are measured.
nlohmann::ordered_json benchVoxelizer(Context& ctx, const VoxelBenchOptions& options);

} // namespace obscura::cli
