#include "scene_options.hpp"

#include "obscura/error.hpp"

#include <cmath>
#include <cstdio>
#include <exception>
#include <string>
#include <vector>

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
    cmd.add_option("--environment", o.environment,
                   "FILE[,intensity[,rotation_deg]]: an equirectangular EXR/HDR lighting the scene (replaces its own)");
}

Environment parseEnvironment(const std::string& text) {
    std::vector<std::string> parts;
    std::size_t start = 0;
    for (std::size_t comma; (comma = text.find(',', start)) != std::string::npos; start = comma + 1)
        parts.push_back(text.substr(start, comma - start));
    parts.push_back(text.substr(start));
    if (parts.empty() || parts[0].empty() || parts.size() > 3)
        throw Error(ErrorCode::Parse, "--environment " + text + ": expected FILE[,intensity[,rotation_deg]]");
    const auto number = [&](const std::string& s, const char* what) {
        try {
            std::size_t used = 0;
            const double v = std::stod(s, &used);
            if (used == s.size() && std::isfinite(v)) return v;
        } catch (const std::exception&) {
        }
        throw Error(ErrorCode::Parse, "--environment " + text + ": " + what + " \"" + s + "\" is not a finite number");
    };
    Environment e;
    e.path = parts[0];
    if (parts.size() > 1) e.intensity = static_cast<float>(number(parts[1], "intensity"));
    if (parts.size() > 2) e.rotation = static_cast<float>(number(parts[2], "rotation_deg") * 3.14159265358979323846 / 180.0);
    if (e.intensity < 0.0f) throw Error(ErrorCode::Parse, "--environment " + text + ": intensity must be >= 0");
    return e;
}

ResolvedScene resolveScene(const SceneOptions& o) {
    ResolvedScene r;
    std::tie(r.width, r.height) = assets::parseImageSize(o.size);
    r.scene = assets::loadScene(o.scene);
    if (!o.environment.empty()) r.scene.scene.environment = parseEnvironment(o.environment);
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
