#include "obscura/assets.hpp"
#include "obscura/error.hpp"

#include <algorithm>
#include <array>
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

namespace {

std::array<glm::vec3, 8> corners(const Bounds& b) {
    std::array<glm::vec3, 8> c;
    for (int i = 0; i < 8; ++i) c[i] = {(i & 1) ? b.max.x : b.min.x, (i & 2) ? b.max.y : b.min.y, (i & 4) ? b.max.z : b.min.z};
    return c;
}

// Nearest and farthest view depth (distance along the view axis) of the bounds' corners.
std::pair<float, float> depthRangeOf(const LookAt& lookAt, const Bounds& b) {
    const glm::vec3 forward = glm::normalize(lookAt.target - lookAt.eye);
    float nearest = INFINITY, farthest = -INFINITY;
    for (const glm::vec3& c : corners(b)) {
        const float z = glm::dot(c - lookAt.eye, forward);
        nearest = std::min(nearest, z);
        farthest = std::max(farthest, z);
    }
    return {nearest, farthest};
}

std::vector<float> parseNumbers(const std::string& text) {
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
    return v;
}

} // namespace

CameraSpec fitDepthRange(const CameraSpec& spec, const Bounds& bounds) {
    if (bounds.empty) return spec;
    const auto [nearest, farthest] = depthRangeOf(spec.lookAt, bounds);
    if (!(farthest > 0.0f)) return spec;
    CameraSpec c = spec;
    c.farPlane = 1.01f * farthest;
    c.nearPlane = std::max(0.9f * nearest, c.farPlane / 1000.0f);
    return c;
}

bool boundsMayBeVisible(const Camera& camera, const Bounds& bounds) {
    if (bounds.empty) return true;
    const glm::mat4 clip = camera.projection * camera.view;
    const auto all = corners(bounds);
    std::array<glm::vec4, 8> h;
    for (int i = 0; i < 8; ++i) h[i] = clip * glm::vec4(all[i], 1.0f);
    // Clip space: inside is -w <= x, y <= w and the depth mode's z range; a plane all eight
    // corners lie outside of hides them all.
    const float zLow = camera.clipDepth == ClipDepth::ZeroToOne ? 0.0f : -1.0f;
    const auto allOutside = [&](auto outside) { return std::all_of(h.begin(), h.end(), outside); };
    return !(allOutside([](const glm::vec4& p) { return p.x < -p.w; }) || allOutside([](const glm::vec4& p) { return p.x > p.w; }) ||
             allOutside([](const glm::vec4& p) { return p.y < -p.w; }) || allOutside([](const glm::vec4& p) { return p.y > p.w; }) ||
             allOutside([&](const glm::vec4& p) { return p.z < zLow * p.w; }) ||
             allOutside([](const glm::vec4& p) { return p.z > p.w; }));
}

CameraSpec parseCameraSpec(const std::string& text, const CameraSpec& base, const Bounds& bounds) {
    const std::vector<float> v = parseNumbers(text);
    if (v.size() != 10 && v.size() != 12)
        throw Error(ErrorCode::Parse, "camera \"" + text +
                                          "\" needs 10 or 12 numbers: ex,ey,ez,tx,ty,tz,ux,uy,uz,fovy_deg[,near,far] (got " +
                                          std::to_string(v.size()) + ")");
    CameraSpec c = base;
    c.lookAt = {{v[0], v[1], v[2]}, {v[3], v[4], v[5]}, {v[6], v[7], v[8]}};
    c.fovyDegrees = v[9];
    if (v.size() == 12) {
        if (!(v[10] > 0.0f && v[10] < v[11] && std::isfinite(v[11])))
            throw Error(ErrorCode::Parse, "camera \"" + text + "\": near and far must satisfy 0 < near < far < inf, got " +
                                              std::to_string(v[10]) + " and " + std::to_string(v[11]));
        c.nearPlane = v[10];
        c.farPlane = v[11];
        return c;
    }
    // The base's planes were chosen for its own eye: kept there, and elsewhere only where
    // they still hold the scene.
    if (c.lookAt.eye == base.lookAt.eye) return c;
    const CameraSpec fitted = fitDepthRange(c, bounds);
    if (base.nearPlane <= fitted.nearPlane && base.farPlane >= fitted.farPlane) return c;
    return fitted;
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
