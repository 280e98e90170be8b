// obscura voxelize: a scene's slicemap voxelization written as grid.json + grid.u8 (one byte
// per voxel, x fastest), optionally as a PLY of voxel cubes.
#include "commands.hpp"
#include "obscura/assets.hpp"
#include "obscura/error.hpp"
#include "obscura/headless.hpp"
#include "obscura/profiler.hpp"
#include "obscura/voxelizer.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>

namespace obscura::cli {
namespace {

constexpr int kSlicesPerTarget = 128; // one RGBA32UI render target

struct VoxelizeOptions {
    std::string scene = "cornell";
    int resolution = 128;
    int slices = 128;
    std::string mode = "surface";
    std::string out;
    bool ply = false;
    int frames = 5;
};

VoxelizerSettings settingsFrom(const VoxelizeOptions& o) {
    VoxelizerSettings s;
    const Setting<VoxelizerSettings>& resolution = *findSetting(VoxelizerSettings::table(), "resolution");
    try {
        resolution.check(o.resolution, "VoxelizerSettings");
    } catch (const Error&) {
        throw Error(ErrorCode::Parse, "--res " + std::to_string(o.resolution) + ": expected one of " + resolution.range);
    }
    s.resolution = o.resolution;
    const int maxSlices = int(findSetting(VoxelizerSettings::table(), "targets")->max) * kSlicesPerTarget;
    if (o.slices % kSlicesPerTarget != 0 || o.slices < kSlicesPerTarget || o.slices > maxSlices)
        throw Error(ErrorCode::Parse, "--slices " + std::to_string(o.slices) + ": expected a multiple of 128 in [128, " +
                                          std::to_string(maxSlices) + "]");
    s.targets = o.slices / kSlicesPerTarget;
    if (o.mode == "surface") s.mode = VoxelMode::Surface;
    else if (o.mode == "solid") s.mode = VoxelMode::Solid;
    else throw Error(ErrorCode::Parse, "--mode " + o.mode + ": expected surface or solid");
    s.dynamic = true; // every timed frame voxelizes again
    return s;
}

void writeGrid(const std::filesystem::path& dir, const std::string& scene, const VoxelizeOptions& o, const VoxelGrid& grid,
               const DenseVoxels& voxels, const std::vector<std::string>& warnings) {
    std::ofstream bytes(dir / "grid.u8", std::ios::binary);
    bytes.write(reinterpret_cast<const char*>(voxels.voxels.data()), static_cast<std::streamsize>(voxels.voxels.size()));
    if (!bytes) throw Error(ErrorCode::Io, "cannot write " + (dir / "grid.u8").string());
    const nlohmann::json meta = {
        {"dims", {grid.dims.x, grid.dims.y, grid.dims.z}},
        {"box_min", {grid.boxMin.x, grid.boxMin.y, grid.boxMin.z}},
        {"box_max", {grid.boxMax.x, grid.boxMax.y, grid.boxMax.z}},
        {"order", "x-fastest"},
        {"scene", scene},
        {"mode", o.mode},
        {"targets", grid.targets},
        {"voxels_set", std::count(voxels.voxels.begin(), voxels.voxels.end(), std::uint8_t{1})},
        {"open_columns", grid.openColumns},
        {"warnings", warnings},
    };
    std::ofstream json(dir / "grid.json");
    json << meta.dump(2) << "\n";
    if (!json) throw Error(ErrorCode::Io, "cannot write " + (dir / "grid.json").string());
}

void runVoxelize(const VoxelizeOptions& o) {
    if (o.frames < 1) throw Error(ErrorCode::Parse, "--frames must be >= 1");
    const VoxelizerSettings settings = settingsFrom(o);
    const assets::LoadedScene scene = assets::loadScene(o.scene);
    const std::filesystem::path dir(o.out);
    std::filesystem::create_directories(dir);

    headless::HeadlessContext gl;
    Context ctx(gl.contextDesc());
    Voxelizer voxelizer(ctx);
    voxelizer.voxelize(scene.scene, settings); // warm-up: shader compilation and allocation
    ctx.profiler().reset();
    for (int i = 0; i < o.frames; ++i) voxelizer.voxelize(scene.scene, settings);
    const VoxelGrid& grid = voxelizer.grid();
    const DenseVoxels voxels = voxelizer.download();
    for (const std::string& w : voxelizer.warnings()) std::fprintf(stderr, "warning: %s\n", w.c_str());
    writeGrid(dir, scene.name, o, grid, voxels, voxelizer.warnings());
    std::printf("scene %s: %d x %d x %d voxels (%s), %zu set, %.1f MiB on the GPU\n", scene.name.c_str(), grid.dims.x,
                grid.dims.y, grid.dims.z, o.mode.c_str(),
                static_cast<std::size_t>(std::count(voxels.voxels.begin(), voxels.voxels.end(), std::uint8_t{1})),
                static_cast<double>(voxelizer.memoryBytes()) / (1024.0 * 1024.0));
    for (const PassStatistics& s : ctx.profiler().statistics(/*wait=*/true))
        std::printf("%-14s median %8.3f ms over %zu frames (%s)\n", s.name.c_str(), s.medianMs, s.samples, toString(s.clock));
    if (o.ply) {
        const glm::dvec3 cell = (grid.boxMax - grid.boxMin) / glm::dvec3(grid.dims);
        assets::writePly(dir / "grid.ply", assets::voxelCubesScene(voxels, grid.boxMin, cell));
    }
    std::printf("wrote %s\n", dir.string().c_str());
}

} // namespace

void addVoxelizeCommand(CLI::App& app) {
    auto options = std::make_shared<VoxelizeOptions>();
    CLI::App* cmd = app.add_subcommand("voxelize", "Voxelize a scene into grid.json + grid.u8 (one byte per voxel)");
    cmd->add_option("--scene", options->scene, "Built-in scene name, JSON scene file, or mesh file")->capture_default_str();
    cmd->add_option("--res", options->resolution,
                    "Voxels along x and y: " + findSetting(VoxelizerSettings::table(), "resolution")->range)
        ->capture_default_str();
    cmd->add_option("--slices", options->slices, "Voxels along z: 128 per render target, [128, 1024]")->capture_default_str();
    cmd->add_option("--mode", options->mode, "surface (OR) or solid (XOR, watertight meshes)")->capture_default_str();
    cmd->add_option("--out", options->out, "Output directory")->required();
    cmd->add_flag("--ply", options->ply, "Also write grid.ply: the set voxels as cubes coloured by render target/channel");
    cmd->add_option("--frames", options->frames, "Timed voxelizations after one warm-up")->capture_default_str();
    cmd->callback([options] { runVoxelize(*options); });
}

} // namespace obscura::cli
