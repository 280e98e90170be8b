// Voxelization example: voxelizes a scene with Obscura on the example's own context (headless
// EGL or a GLFW window) and draws the set voxels as cubes coloured by the channel (hue) and
// render target (lightness) that store them, one tile per mip level.
//
//   obscura_example_voxelization --scene cornell --res 64 --levels 0,1,2 --out voxels.png
//   obscura_example_voxelization --window --frames 0 --scene /usr/share/assimp/models/PLY/Wuson.ply --slices 256
#include "app.hpp"
#include "obscura/error.hpp"
#include "obscura/profiler.hpp"
#include "obscura/voxelizer.hpp"
#include "technique_registry.hpp"

#include <cstdio>
#include <sstream>

using namespace obscura;

namespace {

struct VoxelOptions {
    int resolution = 64;
    int slices = 128;
    std::string mode = "surface";
    std::string levels = "0";
    std::string hierarchy = "octree";
};

std::vector<int> parseLevels(const std::string& text, int top) {
    std::vector<int> levels;
    std::stringstream in(text);
    for (std::string item; std::getline(in, item, ',');) {
        const int l = std::stoi(item);
        if (l < 0 || l > top)
            throw Error(ErrorCode::Parse, "--levels: level " + item + " is outside [0, " + std::to_string(top) + "]");
        levels.push_back(l);
    }
    if (levels.empty()) throw Error(ErrorCode::Parse, "--levels: expected a comma-separated list of levels");
    return levels;
}

// Level L of the octree (cells of 2^L voxels per axis) or of the quadtree (2^L x 2^L
// columns, all slices), as cubes in world units.
Scene levelScene(Voxelizer& voxelizer, int level, bool octree) {
    const VoxelGrid& grid = voxelizer.grid();
    const DenseVoxels cells = level == 0 ? voxelizer.download() : octree ? voxelizer.download(level) : voxelizer.downloadQuadtree(level);
    const double scale = std::ldexp(1.0, level);
    const glm::dvec3 voxel = (grid.boxMax - grid.boxMin) / glm::dvec3(grid.dims);
    Scene scene = assets::voxelCubesScene(cells, grid.boxMin, voxel * glm::dvec3(scale, scale, octree ? scale : 1.0));
    return scene;
}

// A key light from over the camera's shoulder and a dim fill from the other side, so the
// three face orientations of a cube read differently.
void addLights(Scene& scene, const assets::CameraSpec& camera) {
    const glm::vec3 forward = glm::normalize(camera.lookAt.target - camera.lookAt.eye);
    const glm::vec3 right = glm::normalize(glm::cross(forward, camera.lookAt.up));
    const glm::vec3 up = glm::cross(right, forward);
    Light key;
    key.type = LightType::Directional;
    key.direction = forward - 0.6f * right - 0.8f * up;
    key.intensity = 2.5f;
    Light fill = key;
    fill.direction = forward + 0.8f * right + 0.3f * up;
    fill.intensity = 0.8f;
    scene.lights = {key, fill};
}

// Copies `tile` into `picture` at column offset x0.
void blit(TextureImage& picture, const TextureImage& tile, int x0) {
    for (int y = 0; y < tile.height; ++y)
        std::copy_n(tile.rgba.begin() + static_cast<std::ptrdiff_t>(y) * tile.width * 4, tile.width * 4,
                    picture.rgba.begin() + (static_cast<std::ptrdiff_t>(y) * picture.width + x0) * 4);
}

} // namespace

int main(int argc, char** argv) {
    CLI::App parser{"Obscura voxelization example"};
    examples::AppOptions options;
    examples::addAppOptions(parser, options);
    VoxelOptions v;
    parser.add_option("--res", v.resolution, "Voxels along x and y, a power of two in [8, 2048]")->capture_default_str();
    parser.add_option("--slices", v.slices, "Voxels along z, 128 per render target, [128, 1024]")->capture_default_str();
    parser.add_option("--mode", v.mode, "surface or solid")->capture_default_str();
    parser.add_option("--levels", v.levels, "Mip levels to show side by side, e.g. 0,1,2")->capture_default_str();
    parser.add_option("--hierarchy", v.hierarchy, "octree (2^L cells) or quadtree (2^L x 2^L columns)")->capture_default_str();
    CLI11_PARSE(parser, argc, argv);
    return examples::runGuarded([&] {
        if (v.mode != "surface" && v.mode != "solid") throw Error(ErrorCode::Parse, "--mode: expected surface or solid");
        if (v.hierarchy != "octree" && v.hierarchy != "quadtree")
            throw Error(ErrorCode::Parse, "--hierarchy: expected octree or quadtree");
        if (v.slices % 128 != 0) throw Error(ErrorCode::Parse, "--slices: expected a multiple of 128");
        examples::App app(options);
        const assets::LoadedScene scene = assets::loadScene(options.scene);
        const assets::CameraSpec spec =
            options.camera.empty() ? scene.camera
                                   : assets::parseCameraSpec(options.camera, scene.camera, sceneBounds(scene.scene));
        TextureImage shown;
        {
            Context ctx(app.contextDesc());
            Voxelizer voxelizer(ctx);
            VoxelizerSettings settings;
            settings.resolution = v.resolution;
            settings.targets = v.slices / 128;
            settings.mode = v.mode == "solid" ? VoxelMode::Solid : VoxelMode::Surface;
            const VoxelGrid& grid = voxelizer.voxelize(scene.scene, settings);
            for (const std::string& w : voxelizer.warnings()) std::fprintf(stderr, "warning: %s\n", w.c_str());
            const std::vector<int> levels = parseLevels(v.levels, grid.levels);
            const int tileWidth = app.width() / static_cast<int>(levels.size());
            const Camera camera = assets::makeCamera(spec, tileWidth, app.height());
            std::vector<assets::LoadedScene> tiles;
            for (int level : levels) {
                assets::LoadedScene tile = scene;
                tile.scene = levelScene(voxelizer, level, v.hierarchy == "octree");
                addLights(tile.scene, spec);
                tiles.push_back(std::move(tile));
            }
            auto run = cli::techniques().at("gbuffer").create(ctx);
            int presented = 0;
            do {
                TextureImage picture{app.width(), app.height(),
                                     std::vector<std::uint8_t>(static_cast<std::size_t>(app.width()) * app.height() * 4, 0)};
                for (std::size_t i = 0; i < tiles.size(); ++i) {
                    run->run({tiles[i], camera, tileWidth, app.height()});
                    const cli::TechniqueOutput out = run->outputs({"direct"}).front();
                    blit(picture, assets::encodeDisplay(out.display, out.encoding), static_cast<int>(i) * tileWidth);
                }
                shown = app.present(picture);
                ++presented;
            } while (!app.done(presented));
            std::printf("%d x %d x %d voxels, levels %s (%s)\n", grid.dims.x, grid.dims.y, grid.dims.z, v.levels.c_str(),
                        v.hierarchy.c_str());
            examples::printPassTimes(ctx);
        }
        examples::writeShown(options, app.windowed(), shown);
    });
}
