#include "scene_options.hpp"

#include "obscura/error.hpp"

#include <cstdio>

namespace obscura::cli {
namespace {

DepthMode parseDepth(const std::string& s) {
    if (s == "standard") return DepthMode::Standard;
    if (s == "zero_to_one") return DepthMode::StandardZeroToOne;
    if (s == "reversed") return DepthMode::Reversed;
    throw Error(ErrorCode::Parse, "--depth " + s + ": expected standard, zero_to_one or reversed");
}

} // namespace

void addSceneOptions(CLI::App& cmd, SceneOptions& o) {
    cmd.add_option("--scene", o.scene, "Built-in scene name, JSON scene file, or mesh file")->capture_default_str();
    cmd.add_option("--camera", o.camera, "ex,ey,ez,tx,ty,tz,ux,uy,uz,fovy_deg[,near,far] (default: the scene's camera; "
                   "without near,far the planes are fitted to the scene's bounds seen from the eye)");
    cmd.add_option("--size", o.size, "Image size WxH in pixels")->capture_default_str();
    cmd.add_option("--depth", o.depth, "Depth convention: standard, zero_to_one, reversed")->capture_default_str();
}

ResolvedScene resolveScene(const SceneOptions& o) {
    ResolvedScene r;
    std::tie(r.width, r.height) = assets::parseImageSize(o.size);
    r.scene = assets::loadScene(o.scene);
    const Bounds bounds = sceneBounds(r.scene.scene);
    const assets::CameraSpec spec =
        o.camera.empty() ? r.scene.camera : assets::parseCameraSpec(o.camera, r.scene.camera, bounds);
    r.camera = assets::makeCamera(spec, r.width, r.height, parseDepth(o.depth));
    if (!assets::boundsMayBeVisible(r.camera, bounds))
        std::fprintf(stderr,
                     "warning: the whole scene lies outside the camera's view (near %g, far %g world units): the "
                     "image holds no geometry\n",
                     static_cast<double>(spec.nearPlane), static_cast<double>(spec.farPlane));
    return r;
}

} // namespace obscura::cli
