// What the AO tests share: a G-buffer, a voxel grid and the AO module of one scene and
// camera (their open floor is scene_builders.hpp's floorScene).
#pragma once
#include "gl_fixture.hpp"
#include "scene_builders.hpp"

#include "obscura/obscura.hpp"

#include <catch2/catch.hpp>
#include <glm/glm.hpp>

#include <algorithm>
#include <cmath>
#include <functional>

namespace obscura::test {

struct AoFixture {
    GlFixture gl;
    Context ctx{gl.desc()};
    GBuffer gbuffer{ctx};
    Voxelizer voxelizer{ctx};
    AmbientOcclusion ao{ctx};
    GBufferView view;
    Image positions; // view space, alpha = geometry

    //! depthLayers: 2 for ScreenThickness::DepthPeeling.
    void render(const Scene& scene, const Camera& camera, int width, int height, int depthLayers = 1) {
        GBufferSettings settings{width, height, false, {}};
        settings.depthLayers = depthLayers;
        view = gbuffer.render(scene, camera, settings);
        positions = readTexture(ctx, gbuffer.positions(view));
    }

    Image run(const Scene& scene, AmbientOcclusionSettings s, const VoxelizerSettings& voxels = {}) {
        if (s.method == AoMethod::Voxel) s.voxels = &voxelizer.voxelize(scene, voxels);
        return readTexture(ctx, ao.run(view, s).ao);
    }

    bool geometry(int x, int y) const { return positions.at(x, y, 3) > 0.0f; }
    glm::dvec3 world(int x, int y) const {
        const glm::dvec4 v(positions.at(x, y, 0), positions.at(x, y, 1), positions.at(x, y, 2), 1.0);
        return glm::dvec3(glm::inverse(glm::dmat4(view.camera.view)) * v);
    }
};

// AO exactly 1 on every pixel of the fixture's own G-buffer that holds geometry (a plane
// that covers more than half the image).
inline void checkOpenEverywhere(const AoFixture& f, const Image& ao) {
    std::size_t notOne = 0, pixels = 0;
    double lowest = 1.0;
    for (int y = 0; y < ao.height; ++y)
        for (int x = 0; x < ao.width; ++x) {
            if (!f.geometry(x, y)) continue;
            ++pixels;
            notOne += ao.at(x, y, 0) != 1.0f;
            lowest = std::min(lowest, double(ao.at(x, y, 0)));
        }
    INFO(notOne << " of " << pixels << " pixels below 1, lowest " << lowest);
    CHECK(pixels > std::size_t(ao.width * ao.height / 2));
    CHECK(notOne == 0);
}

//! The AO tests' camera: 50 degrees vertical field of view, near 0.05, far 200.
inline Camera lookAt(glm::vec3 eye, glm::vec3 target, int width, int height, DepthMode mode = DepthMode::Standard) {
    return Camera::perspective({eye, target, {0, 1, 0}}, glm::radians(50.0f), float(width) / float(height), 0.05f, 200.0f, mode);
}

// A floor (y = 0) and, facing the camera, a wall in the plane z = -1: floor points at z lie
// D = z + 1 from it. Seen from above the wall's reach, nothing on a floor point's rays is
// hidden from the camera.
inline Scene wallScene() {
    return quadScene({{{glm::dvec3(-20, 0, -20), {-20, 0, 20}, {20, 0, 20}, {20, 0, -20}}},
                      {{glm::dvec3(-20, 0, -1), {20, 0, -1}, {20, 20, -1}, {-20, 20, -1}}}});
}
inline Camera wallCamera(int width, int height) { return lookAt({0, 2.5f, 3.5f}, {0, 0.3f, -0.6f}, width, height); }

//! A `resolution`^3 grid (a multiple of 128) over a fixed box (a test's region of interest,
//! not the scene's bounds).
inline VoxelizerSettings boxVoxels(glm::vec3 boxMin, glm::vec3 boxMax, int resolution = 128) {
    VoxelizerSettings voxels;
    voxels.resolution = resolution;
    voxels.targets = resolution / 128;
    voxels.fitBox = false;
    voxels.boxMin = boxMin;
    voxels.boxMax = boxMax;
    return voxels;
}

//! A grid that covers the wall scene's floor points within 1 m of the wall finely: cubic
//! voxels of side 4 / resolution (kWallVoxelSide at the default 128).
constexpr double kWallVoxelSide = 4.0 / 128.0; // m
inline VoxelizerSettings wallVoxels(int resolution = 128) {
    return boxVoxels({-2.0f, -0.5f, -1.5f}, {2.0f, 3.5f, 2.5f}, resolution);
}

//! Whether pixel (x, y) of the wall scene, as rendered into `f` at W x H, shows a floor point
//! whose rays (radius up to 1) stay inside wallVoxels() and on screen (a margin from the
//! image's border); `p` gets its world position.
inline bool wallFloorPixel(const AoFixture& f, int x, int y, glm::dvec3& p) {
    const int W = f.positions.width;
    if (!f.geometry(x, y)) return false;
    p = f.world(x, y);
    return std::abs(p.y) <= 1e-3 && std::abs(p.x) <= 0.8 && p.z <= 1.2 && x >= 12 && x < W - 12 && y >= 10;
}

// The mean over a floor point's hemisphere of `atHit(d)` for the directions that reach an
// infinite wall at distance d <= reach, and of 1 for the others, the point being `distance`
// from the wall. A direction's component u toward the wall decides: d = distance / u. Cosine-
// weighted directions project uniformly onto the unit disc, where u has density
// 2 sqrt(1 - u^2) / pi; uniform ones have u uniform in [-1, 1] (Archimedes' theorem). So
// mean = 1 - Integral_{distance/reach}^1 (1 - atHit(distance / u)) density(u) du, by
// Simpson's rule on 4096 intervals (atHit is smooth there; the density's square root at u = 1
// leaves an error of order h^1.5, about 1e-6).
inline double wallMean(double distance, double reach, bool cosine, const std::function<double(double)>& atHit) {
    const double c = distance / reach;
    if (c >= 1.0) return 1.0;
    constexpr int n = 4096;
    const double h = (1.0 - c) / n;
    double sum = 0.0;
    for (int i = 0; i <= n; ++i) {
        const double u = c + h * i;
        const double density = cosine ? 2.0 * std::sqrt(std::max(0.0, 1.0 - u * u)) / 3.14159265358979323846 : 0.5;
        const double f = u > 0.0 ? (1.0 - atHit(distance / u)) * density : density;
        sum += f * (i == 0 || i == n ? 1.0 : i % 2 ? 4.0 : 2.0);
    }
    return 1.0 - sum * h / 3.0;
}

// Cosine-weighted AO (no radius limit) at a floor point under a parallel disc of radius a at
// height h, at horizontal distance rho from its axis: one minus the view factor of the disc,
// F = (1 - (h^2 + rho^2 - a^2) / sqrt((h^2 + rho^2 + a^2)^2 - 4 a^2 rho^2)) / 2 (Howell's
// catalogue, element to parallel disc); on the axis 1 - F = h^2 / (h^2 + a^2).
inline double discAo(double rho, double a, double h) {
    const double s = h * h + rho * rho + a * a;
    return 1.0 - 0.5 * (1.0 - (h * h + rho * rho - a * a) / std::sqrt(s * s - 4.0 * a * a * rho * rho));
}

// Every method, and the ray march with each of its depth-buffer marches (their padded Hi-Z
// pyramid included).
struct AoVariant {
    AoMethod method;
    ScreenMarch march = ScreenMarch::View;
    ScreenThickness thickness = ScreenThickness::Constant;
    VoxelTraversal traversal = VoxelTraversal::Hierarchical;
};
inline const AoVariant kAllVariants[] = {{AoMethod::RayMarch, ScreenMarch::View}, {AoMethod::RayMarch, ScreenMarch::Texture},
                                         {AoMethod::RayMarch, ScreenMarch::HiZ},  {AoMethod::Points},
                                         {AoMethod::Horizon},                     {AoMethod::Voxel}};

// AO settings with the variant's method, march, thickness and traversal (the rest default).
inline AmbientOcclusionSettings settingsOf(const AoVariant& variant) {
    AmbientOcclusionSettings s;
    s.method = variant.method;
    s.march = variant.march;
    s.thicknessMode = variant.thickness;
    s.voxelTraversal = variant.traversal;
    return s;
}

inline const char* nameOf(AoMethod m) {
    switch (m) {
    case AoMethod::RayMarch: return "raymarch";
    case AoMethod::Points: return "points";
    case AoMethod::Horizon: return "horizon";
    case AoMethod::Voxel: return "voxel";
    }
    return "?";
}

} // namespace obscura::test
