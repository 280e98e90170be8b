#include "scene_builders.hpp"

#include <glm/gtc/matrix_inverse.hpp>

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

glm::dvec2 pixelNdc(int x, int y, int width, int height) {
    return {(x + 0.5) / width * 2.0 - 1.0, 1.0 - (y + 0.5) / height * 2.0};
}

ViewRay pixelRay(const Camera& camera, int x, int y, int width, int height) {
    const glm::dvec2 ndc = pixelNdc(x, y, width, height);
    const glm::dmat4 p(camera.projection);
    if (p[2][3] == -1.0) // perspective: x_ndc = (p00 x + p20 z) / -z
        return {{0, 0, 0}, {(ndc.x + p[2][0]) / p[0][0], (ndc.y + p[2][1]) / p[1][1], -1.0}};
    return {{(ndc.x - p[3][0]) / p[0][0], (ndc.y - p[3][1]) / p[1][1], 0.0}, {0, 0, -1.0}};
}

} // namespace obscura::test
