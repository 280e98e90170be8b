#pragma once
// obscura::assets: scenes and images for tools, tests, examples and benchmarks.
//
// Scene sources: built-in scenes (the Cornell box and analytic test scenes), a JSON scene
// description (docs/scene-format.md), or any mesh file assimp reads (OBJ, PLY, glTF/GLB,
// Collada, ...). Images: EXR/HDR/PNG/JPEG/TGA through OpenImageIO.
#include "obscura/camera.hpp"
#include "obscura/export.hpp"
#include "obscura/scene.hpp"
#include "obscura/texture.hpp"
#include "obscura/voxelizer.hpp"

#include <filesystem>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace obscura::assets {

//! A viewpoint: where to look from and the vertical field of view.
struct CameraSpec {
    LookAt lookAt;
    float fovyDegrees = 45.0f; //!< vertical, degrees, (0, 180)
    float nearPlane = 0.1f;    //!< world units, (0, farPlane)
    float farPlane = 100.0f;   //!< world units, (nearPlane, inf)
};

struct LoadedScene {
    std::string name;
    Scene scene;
    CameraSpec camera;          //!< the scene's own camera, or one framing its bounds
    float unitsPerMetre = 1.0f; //!< e.g. 1000 for the Cornell box (millimetres)
};

//! "cornell" (its emitter as a point light), "cornell_sphere" and "cornell_rect" (as a sphere
//! or rect light), "plane", "wall", "corner", "box_room".
OBSCURA_API std::vector<std::string> builtinSceneNames();
//! Throws Error{InvalidArgument} listing the names for an unknown one.
OBSCURA_API LoadedScene builtinScene(const std::string& name);
//! Throws Error{Io} or Error{Parse} with the file and the JSON path of the problem.
OBSCURA_API LoadedScene loadJsonScene(const std::filesystem::path& path);
//! Any format assimp reads; the node hierarchy is flattened. Throws Error{Io}/Error{Parse}.
OBSCURA_API LoadedScene loadMeshFile(const std::filesystem::path& path);
//! A built-in name, a .json file, or a mesh file.
OBSCURA_API LoadedScene loadScene(const std::string& source);

//! Parses "ex,ey,ez,tx,ty,tz,ux,uy,uz,fovy_deg[,near,far]" (lookAt, vertical fovy in degrees,
//! optionally the near and far planes in world units, 0 < near < far). Without near and far
//! they are `base`'s at base's own eye (the scene's own camera spelled out is unchanged) and
//! where they hold `bounds` seen from the new eye, else fitDepthRange's.
//! Throws Error{Parse} for a count other than 10 or 12, a word that is not a number, or
//! planes outside 0 < near < far < inf.
OBSCURA_API CameraSpec parseCameraSpec(const std::string& text, const CameraSpec& base, const Bounds& bounds = {});
//! `spec` with near and far planes that hold `bounds` seen from its eye along its view axis:
//! far 1 % past the farthest corner's view depth, near 0.9 of the nearest corner's, but at
//! least far / 1000 (with the eye inside the bounds or beside them, the nearest corner's depth
//! is 0 or less; 1000 keeps a 32F depth's relative precision near 1e-5, camera.hpp). Unchanged
//! for empty bounds or bounds wholly behind the eye (nothing to hold).
OBSCURA_API CameraSpec fitDepthRange(const CameraSpec& spec, const Bounds& bounds);
//! False when `bounds` lie wholly outside `camera`'s view volume (all eight corners outside
//! one of its six planes): the picture has no geometry at all. True otherwise (a box that
//! straddles a frustum's edge may still miss it; a cheap test, for warnings). True for empty
//! bounds.
OBSCURA_API bool boundsMayBeVisible(const Camera& camera, const Bounds& bounds);
//! Parses "WxH" (pixels, both >= 1). Throws Error{Parse}.
OBSCURA_API std::pair<int, int> parseImageSize(const std::string& text);
//! A standard-depth perspective camera for an image of width x height pixels.
OBSCURA_API Camera makeCamera(const CameraSpec& spec, int width, int height, DepthMode mode = DepthMode::Standard);
//! A spec that frames the bounds from a three-quarter view.
OBSCURA_API CameraSpec framingCamera(const Bounds& bounds, float fovyDegrees = 45.0f);

enum class PngEncoding {
    Srgb,   //!< values are linear; apply the sRGB transfer function (colours, radiance)
    Linear, //!< write values as they are (already display-mapped data: normals * 0.5 + 0.5, AO)
};

//! A path's extension in lower case (".exr" for "AO.EXR"; empty without one): how the image
//! and scene readers and writers tell formats apart.
OBSCURA_API std::string lowerExtension(const std::filesystem::path& path);
//! Reads an image as float (sRGB 8-bit files are linearized). Throws Error{Io}.
OBSCURA_API Image readImage(const std::filesystem::path& path);
//! Writes .exr (float, values as they are, any number of channels) or .png (8-bit, 1 to 4
//! channels, clamped to [0,1] after the encoding). Other extensions throw Error{InvalidArgument}; failures Error{Io}.
OBSCURA_API void writeImage(const std::filesystem::path& path, const Image& image,
                            PngEncoding encoding = PngEncoding::Srgb);
//! The 8-bit RGBA picture a PNG of `image` contains (row 0 at the top): 1 channel becomes
//! grey, 3 get alpha 255; values are encoded, clamped to [0,1] and rounded to nearest.
OBSCURA_API TextureImage encodeDisplay(const Image& image, PngEncoding encoding);
//! Writes an 8-bit RGBA picture as PNG. Throws Error{Io}.
OBSCURA_API void writePng(const std::filesystem::path& path, const TextureImage& picture);

//! An sRGB RGBA8 texture from any image file (for Material::albedoImage).
OBSCURA_API TextureImage readTextureImage(const std::filesystem::path& path);

//! The set cells of a voxel grid as cubes: only faces between a set and an empty cell (or
//! the grid's edge), two triangles each, with outward normals. Cell (x, y, z) spans
//! origin + cellSize * [(x, y, z), (x, y, z) + 1] (world units). One mesh and material per
//! colour group: cells of slice z go to group z / 32, i.e. channel (z / 32) % 4 (hue: red,
//! green, blue, amber) of render target z / 128 (lighter for later targets) of the slicemap
//! that stores them.
OBSCURA_API Scene voxelCubesScene(const DenseVoxels& voxels, const glm::dvec3& origin, const glm::dvec3& cellSize);
//! Writes the scene's CPU meshes (model transforms applied) as one binary little-endian PLY
//! with per-vertex colours from the material albedo (sRGB 8-bit). Throws Error{Io}.
OBSCURA_API void writePly(const std::filesystem::path& path, const Scene& scene);

} // namespace obscura::assets
