#include "scene_builders.hpp"

#include <glm/gtc/constants.hpp>
#include <glm/gtc/matrix_inverse.hpp>

#include <algorithm>
#include <cmath>
#include <map>

namespace obscura::test {

std::shared_ptr<MeshData> quadMesh(const QuadCorners& c, bool withNormals) {
    auto m = std::make_shared<MeshData>();
    const glm::dvec3 n = glm::normalize(glm::cross(c[1] - c[0], c[2] - c[0]));
    for (const auto& v : c) {
        m->positions.emplace_back(v);
        if (withNormals) m->normals.emplace_back(n);
    }
    m->indices = {0, 1, 2, 0, 2, 3};
    return m;
}

std::shared_ptr<MeshData> cubeMesh() {
    auto m = std::make_shared<MeshData>();
    for (int i = 0; i < 8; ++i) m->positions.emplace_back(i & 1, (i >> 1) & 1, (i >> 2) & 1);
    // Two triangles per face, counter-clockwise seen from outside.
    m->indices = {0, 2, 3, 0, 3, 1, 4, 5, 7, 4, 7, 6, 0, 1, 5, 0, 5, 4,
                  2, 6, 7, 2, 7, 3, 0, 4, 6, 0, 6, 2, 1, 3, 7, 1, 7, 5};
    return m;
}

std::shared_ptr<MeshData> icosphereMesh(int subdivisions) {
    auto m = std::make_shared<MeshData>();
    const float g = (1.0f + std::sqrt(5.0f)) / 2.0f;
    for (const glm::vec3 v : {glm::vec3(-1, g, 0), glm::vec3(1, g, 0), glm::vec3(-1, -g, 0), glm::vec3(1, -g, 0),
                              glm::vec3(0, -1, g), glm::vec3(0, 1, g), glm::vec3(0, -1, -g), glm::vec3(0, 1, -g),
                              glm::vec3(g, 0, -1), glm::vec3(g, 0, 1), glm::vec3(-g, 0, -1), glm::vec3(-g, 0, 1)})
        m->positions.push_back(glm::normalize(v));
    m->indices = {0, 11, 5, 0, 5, 1, 0, 1, 7, 0, 7, 10, 0, 10, 11, 1, 5, 9, 5, 11, 4, 11, 10, 2, 10, 7, 6, 7, 1, 8,
                  3, 9, 4, 3, 4, 2, 3, 2, 6, 3, 6, 8, 3, 8, 9, 4, 9, 5, 2, 4, 11, 6, 2, 10, 8, 6, 7, 9, 8, 1};
    for (int s = 0; s < subdivisions; ++s) {
        // Each edge's midpoint once (shared by its two triangles), so the mesh stays closed.
        std::map<std::pair<std::uint32_t, std::uint32_t>, std::uint32_t> midpoints;
        const auto midpoint = [&](std::uint32_t a, std::uint32_t b) {
            const auto key = std::minmax(a, b);
            const auto [it, added] = midpoints.emplace(key, static_cast<std::uint32_t>(m->positions.size()));
            if (added) m->positions.push_back(glm::normalize(m->positions[a] + m->positions[b]));
            return it->second;
        };
        std::vector<std::uint32_t> finer;
        for (std::size_t i = 0; i < m->indices.size(); i += 3) {
            const std::uint32_t a = m->indices[i], b = m->indices[i + 1], c = m->indices[i + 2];
            const std::uint32_t ab = midpoint(a, b), bc = midpoint(b, c), ca = midpoint(c, a);
            finer.insert(finer.end(), {a, ab, ca, b, bc, ab, c, ca, bc, ab, bc, ca});
        }
        m->indices = std::move(finer);
    }
    return m;
}

Scene singleMeshScene(std::shared_ptr<const MeshData> mesh, const glm::mat4& model) {
    Scene s;
    s.materials.push_back(Material{});
    Mesh m;
    m.data = std::move(mesh);
    m.model = model;
    s.meshes.push_back(m);
    return s;
}

std::optional<double> AnalyticQuad::intersect(const glm::dvec3& o, const glm::dvec3& d) const {
    const glm::dvec3 n = normal();
    const double denom = glm::dot(n, d);
    if (denom == 0.0) return std::nullopt;
    const double t = glm::dot(n, corners[0] - o) / denom;
    if (!(t > 0.0)) return std::nullopt;
    const glm::dvec3 p = o + t * d;
    // Inside a convex polygon: p is on the same side of every edge.
    for (int i = 0; i < 4; ++i) {
        const glm::dvec3 e = corners[(i + 1) % 4] - corners[i];
        if (glm::dot(glm::cross(e, p - corners[i]), n) < 0.0) return std::nullopt;
    }
    return t;
}

glm::dvec3 AnalyticQuad::normal() const {
    return glm::normalize(glm::cross(corners[1] - corners[0], corners[2] - corners[0]));
}

Scene quadScene(const std::vector<AnalyticQuad>& quads, glm::vec3 albedo) {
    Scene s;
    Material m;
    m.albedo = albedo;
    s.materials.push_back(m);
    for (const auto& q : quads) {
        Mesh mesh;
        mesh.data = quadMesh(q.corners);
        s.meshes.push_back(mesh);
    }
    return s;
}

Scene floorScene(double half) {
    return quadScene({{{glm::dvec3(-half, 0, -half), {-half, 0, half}, {half, 0, half}, {half, 0, -half}}}});
}

Scene cornerScene(bool lit) {
    const AnalyticQuad floor{{{{-3, 0, -3}, {-3, 0, 3}, {3, 0, 3}, {3, 0, -3}}}};
    const AnalyticQuad wall{{{{-3, 0, -1}, {3, 0, -1}, {3, 2, -1}, {-3, 2, -1}}}};
    Scene scene = quadScene({floor, wall});
    if (lit) {
        Light light;
        light.position = {0.5f, 1.5f, 1.0f};
        light.intensity = 3.0f;
        scene.lights.push_back(light);
    }
    return scene;
}

Scene withSun(Scene scene) {
    Light sun;
    sun.type = LightType::Directional;
    sun.direction = glm::vec3(0.3f, -1.0f, 0.2f);
    sun.intensity = 3.0f;
    scene.lights.push_back(sun);
    return scene;
}

Scene withDisc(Scene scene, double a, double h) {
    auto disc = std::make_shared<MeshData>();
    constexpr int n = 256;
    const double pi = glm::pi<double>();
    const double r = a * std::sqrt(2.0 * pi / n / std::sin(2.0 * pi / n)); // equal area
    disc->positions.push_back(glm::vec3(0.0f, float(h), 0.0f));
    for (int i = 0; i < n; ++i)
        disc->positions.push_back(glm::vec3(float(r * std::cos(2.0 * pi * i / n)), float(h), float(r * std::sin(2.0 * pi * i / n))));
    for (int i = 0; i < n; ++i)
        for (const std::uint32_t v : {0u, std::uint32_t(1 + i), std::uint32_t(1 + (i + 1) % n)}) disc->indices.push_back(v);
    scene.meshes.push_back({disc, glm::mat4(1.0f), 0, "disc"});
    return scene;
}

glm::dvec2 pixelNdc(int x, int y, int width, int height) {
    return {(x + 0.5) / width * 2.0 - 1.0, 1.0 - (y + 0.5) / height * 2.0};
}

glm::dvec3 texel3(const Image& image, int x, int y) { return {image.at(x, y, 0), image.at(x, y, 1), image.at(x, y, 2)}; }

glm::dvec3 worldPoint(const Image& viewPositions, const glm::dmat4& toWorld, int x, int y) {
    return glm::dvec3(toWorld * glm::dvec4(texel3(viewPositions, x, y), 1.0));
}

Camera cornellCamera(int width, int height) {
    return Camera::perspective({{278, 273, -700}, {278, 273, 0}, {0, 1, 0}}, glm::radians(40.0f),
                               float(width) / float(height), 10.0f, 5000.0f);
}

ViewRay pixelRay(const Camera& camera, int x, int y, int width, int height) {
    const glm::dvec2 ndc = pixelNdc(x, y, width, height);
    const glm::dmat4 p(camera.projection);
    if (p[2][3] == -1.0) // perspective: x_ndc = (p00 x + p20 z) / -z
        return {{0, 0, 0}, {(ndc.x + p[2][0]) / p[0][0], (ndc.y + p[2][1]) / p[1][1], -1.0}};
    return {{(ndc.x - p[3][0]) / p[0][0], (ndc.y - p[3][1]) / p[1][1], 0.0}, {0, 0, -1.0}};
}

} // namespace obscura::test
