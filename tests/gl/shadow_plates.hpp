// The plate scenes of the shadow-map tests: a square plate 1 m above a 40 m floor, the views
// and lights they use, and the check of a mask against the Embree reference away from the
// shadow's edge. Shared by test_shadow_maps.cpp and test_soft_shadows.cpp.
#pragma once
#include "gl_fixture.hpp"
#include "scene_builders.hpp"

#include "obscura/obscura.hpp"
#include "obscura/reference.hpp"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>

namespace obscura::test {

inline constexpr double kPlate = 0.5, kHeight = 1.0; // the plate: [-0.5, 0.5]^2 at y = 1

inline Scene plateScene(const Light& light) {
    Scene s = test::quadScene({{{glm::dvec3(-20, 0, -20), {-20, 0, 20}, {20, 0, 20}, {20, 0, -20}}},
                               {{glm::dvec3(-kPlate, kHeight, -kPlate), {-kPlate, kHeight, kPlate}, {kPlate, kHeight, kPlate},
                                 {kPlate, kHeight, -kPlate}}}});
    s.lights = {light};
    return s;
}

// The plate tests' view: the plate and its shadow from above and in front, W x H pixels.
inline Camera plateCamera(int w, int h) {
    return Camera::perspective({{0, 3.5f, 4.5f}, {0, 0.3f, 0}, {0, 1, 0}}, 0.9f, float(w) / float(h), 0.05f, 100.0f);
}

// A spot light pointing down, its cone's edge out of the plate tests' view.
inline Light downwardSpot(glm::vec3 position) {
    Light spot;
    spot.type = LightType::Spot;
    spot.position = position;
    spot.direction = {0.0f, -1.0f, 0.0f};
    spot.outerAngle = 1.2f;
    spot.innerAngle = 1.0f;
    return spot;
}

// Distance on the floor from (x, z) to the outline of the square of half side a centred at c.
inline double squareEdgeDistance(double x, double z, glm::dvec2 c, double a) {
    const glm::dvec2 q = glm::abs(glm::dvec2(x, z) - c) - glm::dvec2(a);
    const double outside = glm::length(glm::max(q, glm::dvec2(0.0)));
    return outside > 0.0 ? outside : -std::max(q.x, q.y);
}

// A thin upright wall (x = 0, |z| <= 1, y in [0, 1]) on a floor, a spot light on its +x side:
// with a constant bias longer than the wall is thick, receivers just behind its base are
// carried through it (peter-panning). The contact-shadow tests' scene, and their camera.
inline Scene contactWallScene(glm::vec3 albedo = glm::vec3(0.5f)) {
    Light spot;
    spot.type = LightType::Spot;
    spot.position = {3.0f, 2.5f, 0.0f};
    spot.direction = glm::normalize(glm::vec3(-3.5f, -2.5f, 0.0f));
    spot.outerAngle = 1.0f;
    Scene scene = test::quadScene({{{glm::dvec3(-20, 0, -20), {-20, 0, 20}, {20, 0, 20}, {20, 0, -20}}},
                                   {{glm::dvec3(0, 0, -1), {0, 0, 1}, {0, 1, 1}, {0, 1, -1}}}},
                                  albedo);
    scene.lights = {spot};
    return scene;
}
inline Camera contactWallCamera(int w, int h) {
    return Camera::perspective({{-3.0f, 2.5f, 2.0f}, {-0.5f, 0.2f, 0}, {0, 1, 0}}, 0.9f, float(w) / float(h), 0.05f, 100.0f);
}

struct ShadowFixture {
    test::GlFixture gl;
    Context ctx{gl.desc()};
    GBuffer gbuffer{ctx};
    ShadowMaps shadows{ctx};
    GBufferView view;
    Image positions;
    Camera camera;
    int width, height;

    ShadowFixture(const Camera& c, int w, int h) : camera(c), width(w), height(h) {}

    void render(const Scene& scene) {
        view = gbuffer.render(scene, camera, {width, height, false, {}});
        positions = readTexture(ctx, gbuffer.positions(view));
    }
    glm::dvec3 world(int x, int y) const {
        const glm::dvec4 v(positions.at(x, y, 0), positions.at(x, y, 1), positions.at(x, y, 2), 1.0);
        return glm::dvec3(glm::inverse(glm::dmat4(camera.view)) * v);
    }
    reference::Reference truth(const Scene& scene) {
        const reference::RayScene rays(scene);
        const reference::ShadingPoints points =
            reference::fromGBuffer(rays, camera, positions, readTexture(ctx, view.normal));
        reference::RenderSettings rs;
        rs.samplesPerPixel = 2; // hard lights: one sample is exact
        return reference::render(rays, points, reference::Shadow{0}, rs);
    }
};

// Checks a mask against the reference: every pixel the light reaches and that lies farther
// than `band(p)` world units from the shadow's edge on the floor (plate pixels: anywhere)
// has the reference's value exactly (0 or 1); returns the pixels compared.
template <typename Band, typename Edge>
inline int checkMask(const ShadowFixture& f, const Image& mask, const reference::Reference& truth, Band band, Edge edge) {
    int compared = 0, shadowed = 0;
    for (int y = 0; y < f.height; ++y)
        for (int x = 0; x < f.width; ++x) {
            const std::size_t i = std::size_t(y) * std::size_t(f.width) + std::size_t(x);
            if (f.positions.at(x, y, 3) == 0.0f || truth.value.pixels[2 * i + 1] == 0.0f) continue;
            const glm::dvec3 p = f.world(x, y);
            const bool onFloor = std::abs(p.y) < 1e-3;
            if (onFloor && std::abs(edge(p)) <= band(p)) continue;
            const float expected = truth.value.pixels[2 * i];
            CAPTURE(x, y, p.x, p.y, p.z, expected, mask.at(x, y, 0));
            CHECK(mask.at(x, y, 0) == expected);
            ++compared;
            shadowed += expected == 0.0f ? 1 : 0;
        }
    CHECK(shadowed > 20);
    return compared;
}

} // namespace obscura::test
