#pragma once
// Small geometry and shading-point builders for the reference tests.
#include "obscura/reference.hpp"
#include "scene_builders.hpp"

#include <cmath>
#include <vector>

namespace obscura::test {

constexpr double kPi = 3.14159265358979323846;

//! A regular polygon of `segments` sides inscribed in the circle (centre, radius), in the
//! plane y = centre.y, as a triangle fan.
inline std::shared_ptr<MeshData> discMesh(const glm::dvec3& centre, double radius, int segments) {
    auto m = std::make_shared<MeshData>();
    m->positions.emplace_back(centre);
    for (int i = 0; i < segments; ++i) {
        const double a = 2 * kPi * i / segments;
        m->positions.emplace_back(centre + radius * glm::dvec3(std::cos(a), 0, std::sin(a)));
    }
    for (int i = 0; i < segments; ++i)
        m->indices.insert(m->indices.end(), {0u, 1u + static_cast<std::uint32_t>(i),
                                             1u + static_cast<std::uint32_t>((i + 1) % segments)});
    return m;
}

//! A scene of meshes with one white material.
inline Scene meshScene(const std::vector<std::shared_ptr<MeshData>>& meshes, glm::vec3 albedo = glm::vec3(1.0f)) {
    Scene s;
    Material m;
    m.albedo = albedo;
    s.materials.push_back(m);
    for (const auto& d : meshes) s.meshes.push_back({d, glm::mat4(1.0f), 0, "mesh"});
    return s;
}

//! Surface points seen from straight above along their normal (one per pixel, in a row).
inline reference::ShadingPoints pointsAt(const std::vector<glm::dvec3>& positions, const glm::dvec3& normal,
                                         const glm::dvec3& albedo = glm::dvec3(1.0)) {
    reference::ShadingPoints pts{static_cast<int>(positions.size()), 1, {}};
    for (const auto& p : positions) {
        reference::ShadingPoint s;
        s.origin = p + normal;
        s.direction = -normal;
        s.distance = 1.0;
        s.position = p;
        s.normal = s.shadingNormal = normal;
        s.albedo = albedo;
        pts.points.push_back(s);
    }
    return pts;
}

//! `count` copies of the same view ray without a surface (for media): independent pixels.
inline reference::ShadingPoints repeatedRay(const glm::dvec3& origin, const glm::dvec3& direction, int count) {
    reference::ShadingPoints pts{count, 1, {}};
    reference::ShadingPoint s;
    s.origin = origin;
    s.direction = glm::normalize(direction);
    pts.points.assign(static_cast<std::size_t>(count), s);
    return pts;
}

//! Mean and standard deviation of channel c over the pixels of an image.
struct Stats {
    double mean = 0, stddev = 0;
    std::size_t n = 0;
};
inline Stats stats(const Image& img, int c) {
    Stats s;
    s.n = static_cast<std::size_t>(img.width) * img.height;
    for (std::size_t i = 0; i < s.n; ++i) s.mean += img.pixels[i * img.channels + c];
    s.mean /= double(s.n);
    for (std::size_t i = 0; i < s.n; ++i) {
        const double d = img.pixels[i * img.channels + c] - s.mean;
        s.stddev += d * d;
    }
    s.stddev = std::sqrt(s.stddev / double(s.n - 1));
    return s;
}

} // namespace obscura::test
