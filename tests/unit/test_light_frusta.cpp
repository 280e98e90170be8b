// The cameras of shadow maps: cascade splits, the visible distance range, and the texel
// snapping that keeps directional cascades still when the camera moves.
#include "shadows/light_frusta.hpp"

#include <catch2/catch.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include <cmath>

using namespace obscura;
using namespace obscura::detail;

namespace {

Bounds box(glm::vec3 lo, glm::vec3 hi) { return {lo, hi, false}; }

// The light-space texel grid position of the map's centre: world -> clip of the map, then
// the clip x, y of the world origin in texels.
glm::dvec2 originInTexels(const LightCamera& lc, int resolution) {
    const glm::dvec4 clip = glm::dmat4(lc.camera.projection) * glm::dmat4(lc.camera.view) * glm::dvec4(0, 0, 0, 1);
    return glm::dvec2(clip) * (0.5 * resolution);
}

} // namespace

TEST_CASE("Cascade splits are uniform at lambda 0 logarithmic at lambda 1 and end at the far distance", "[unit][shadows]") {
    const auto uniform = cascadeSplits(1.0, 101.0, 4, 0.0);
    const auto logarithmic = cascadeSplits(1.0, 10000.0, 4, 1.0);
    REQUIRE(uniform.size() == 4);
    for (int i = 0; i < 4; ++i) {
        CHECK(uniform[std::size_t(i)] == Approx(1.0 + 25.0 * (i + 1)));
        CHECK(logarithmic[std::size_t(i)] == Approx(std::pow(10.0, i + 1)));
    }
    CHECK(cascadeSplits(0.1, 1e6, 3, 0.5).back() == 1e6);
}

TEST_CASE("The visible distances are the scene's depth range clipped to the near and far planes", "[unit][shadows]") {
    const Camera camera = Camera::perspective({{0, 0, 10}, {0, 0, 0}, {0, 1, 0}}, 1.0f, 1.0f, 0.5f, 100.0f);
    const DistanceRange r = visibleDistances(camera, box({-1, -1, -1}, {1, 1, 1}));
    CHECK(r.nearest == Approx(9.0));
    CHECK(r.farthest == Approx(11.0));
    // A scene around the camera: from the near plane; one beyond the far plane: a fallback.
    CHECK(visibleDistances(camera, box({-50, -50, -50}, {50, 50, 50})).nearest == Approx(0.5));
    const DistanceRange behind = visibleDistances(camera, box({-1, -1, 20}, {1, 1, 30}));
    CHECK(behind.farthest > behind.nearest);
}

TEST_CASE("Directional cascades move by whole texels when the camera moves and keep their size when it turns", "[unit][shadows]") {
    const Bounds scene = box({-50, 0, -50}, {50, 10, 50});
    const glm::dvec3 sun = glm::normalize(glm::dvec3(-0.4, -1.0, -0.6));
    constexpr int resolution = 1024;
    const LightCamera a = directionalCascade(sun, Camera::perspective({{0, 2, 5}, {0, 0, 0}, {0, 1, 0}}, 1.0f, 1.5f, 0.1f, 200.0f),
                                             0.1, 20.0, scene, resolution);
    for (const glm::vec3 shift : {glm::vec3(0.0123f, 0.0f, 0.0f), glm::vec3(0.3f, 0.01f, -0.7f)}) {
        const Camera moved = Camera::perspective({glm::vec3(0, 2, 5) + shift, shift, {0, 1, 0}}, 1.0f, 1.5f, 0.1f, 200.0f);
        const LightCamera b = directionalCascade(sun, moved, 0.1, 20.0, scene, resolution);
        CHECK(b.texelSize == a.texelSize);
        const glm::dvec2 d = originInTexels(b, resolution) - originInTexels(a, resolution);
        CAPTURE(d.x, d.y);
        // Whole texels, up to the float rounding of the map's camera (a few ulp of its extent
        // in texels: about resolution x 1e-6).
        CHECK(std::abs(d.x - std::round(d.x)) < 1e-2);
        CHECK(std::abs(d.y - std::round(d.y)) < 1e-2);
    }
    const Camera turned = Camera::perspective({{0, 2, 5}, {3, 1, 0}, {0, 1, 0}}, 1.0f, 1.5f, 0.1f, 200.0f);
    CHECK(directionalCascade(sun, turned, 0.1, 20.0, scene, resolution).texelSize == a.texelSize);
}

TEST_CASE("A light parallel to the world's up axis gets a valid map camera", "[unit][shadows][stability]") {
    const Bounds scene = box({-1, 0, -1}, {1, 1, 1});
    const Camera camera = Camera::perspective({{0, 2, 5}, {0, 0, 0}, {0, 1, 0}}, 1.0f, 1.0f, 0.1f, 100.0f);
    for (const glm::dvec3 d : {glm::dvec3(0, -1, 0), glm::dvec3(0, 1, 0), glm::dvec3(1e-9, -1, 0)}) {
        const LightCamera lc = directionalCascade(d, camera, 0.1, 10.0, scene, 512);
        const glm::mat4 m = lc.camera.projection * lc.camera.view;
        for (int c = 0; c < 4; ++c)
            for (int r = 0; r < 4; ++r) CHECK(std::isfinite(m[c][r]));
        CHECK(std::abs(glm::dot(glm::normalize(glm::dvec3(lightUp(d))), glm::normalize(d))) < 0.95);
    }
    Light spot;
    spot.type = LightType::Spot;
    spot.position = {0, 5, 0};
    spot.direction = {0, -1, 0};
    const LightCamera s = spotCamera(spot, scene, 512);
    CHECK(std::isfinite(s.texelSize));
    CHECK(analyzeProjection(s.camera).reversedZ);
}
