#include "obscura/assets.hpp"
#include "obscura/error.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

namespace obscura::assets {

LoadedScene loadScene(const std::string& source) {
    const auto names = builtinSceneNames();
    if (std::find(names.begin(), names.end(), source) != names.end()) return builtinScene(source);
    const std::filesystem::path path(source);
    const std::string ext = lowerExtension(path);
    if (ext == ".json") return loadJsonScene(path);
    if (ext.empty() && !std::filesystem::exists(path)) {
        std::string known;
        for (const auto& n : names) known += (known.empty() ? "" : ", ") + n;
        throw Error(ErrorCode::InvalidArgument,
                    "scene \"" + source + "\" is neither a built-in scene (" + known + ") nor a file");
    }
    return loadMeshFile(path);
}

CameraSpec parseCameraSpec(const std::string& text, const CameraSpec& base) {
    std::vector<float> v;
    std::stringstream in(text);
    std::string item;
    while (std::getline(in, item, ',')) {
        try {
            std::size_t used = 0;
            v.push_back(std::stof(item, &used));
            if (used != item.size()) throw std::invalid_argument(item);
        } catch (const std::exception&) {
            throw Error(ErrorCode::Parse, "camera \"" + text + "\": \"" + item + "\" is not a number");
        }
    }
    if (v.size() != 10)
        throw Error(ErrorCode::Parse, "camera \"" + text + "\" needs 10 numbers: ex,ey,ez,tx,ty,tz,ux,uy,uz,fovy_deg (got " +
                                          std::to_string(v.size()) + ")");
    CameraSpec c = base;
    c.lookAt = {{v[0], v[1], v[2]}, {v[3], v[4], v[5]}, {v[6], v[7], v[8]}};
    c.fovyDegrees = v[9];
    return c;
}

std::pair<int, int> parseImageSize(const std::string& text) {
    int w = 0, h = 0;
    char x = 0, extra = 0;
    if (std::sscanf(text.c_str(), "%d%c%d%c", &w, &x, &h, &extra) != 3 || x != 'x' || w < 1 || h < 1)
        throw Error(ErrorCode::Parse, "size \"" + text + "\": expected WxH with W, H >= 1 (e.g. 256x256)");
    return {w, h};
}

Camera makeCamera(const CameraSpec& spec, int width, int height, DepthMode mode) {
    if (width < 1 || height < 1)
        throw Error(ErrorCode::InvalidArgument, "makeCamera: image size must be >= 1x1, got " + std::to_string(width) + "x" +
                                                    std::to_string(height));
    if (!(spec.fovyDegrees > 0.0f && spec.fovyDegrees < 180.0f))
        throw Error(ErrorCode::InvalidArgument, "camera fovy must be in (0, 180) degrees, got " +
                                                    std::to_string(spec.fovyDegrees));
    const float fovy = spec.fovyDegrees * 3.14159265358979f / 180.0f;
    return Camera::perspective(spec.lookAt, fovy, static_cast<float>(width) / static_cast<float>(height), spec.nearPlane,
                               spec.farPlane, mode);
}

CameraSpec framingCamera(const Bounds& bounds, float fovyDegrees) {
    CameraSpec c;
    c.fovyDegrees = fovyDegrees;
    const glm::vec3 centre = bounds.empty ? glm::vec3(0.0f) : 0.5f * (bounds.min + bounds.max);
    float radius = bounds.empty ? 1.0f : 0.5f * glm::length(bounds.max - bounds.min);
    if (!(radius > 0.0f)) radius = 1.0f;
    const float halfFov = 0.5f * fovyDegrees * 3.14159265358979f / 180.0f;
    const float distance = 1.1f * radius / std::sin(halfFov);
    const glm::vec3 direction = glm::normalize(glm::vec3(0.6f, 0.45f, 1.0f));
    c.lookAt = {centre + direction * distance, centre, {0.0f, 1.0f, 0.0f}};
    c.nearPlane = std::max(distance - 1.5f * radius, 0.01f * radius);
    c.farPlane = distance + 2.0f * radius;
    return c;
}

} // namespace obscura::assets
