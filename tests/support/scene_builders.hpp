#pragma once
// Small scenes built in code for tests with a closed-form answer.
#include "obscura/camera.hpp"
#include "obscura/scene.hpp"
#include "obscura/texture.hpp"

#include <array>
#include <memory>
#include <optional>
#include <vector>

namespace obscura::test {

using QuadCorners = std::array<glm::dvec3, 4>;

//! Two triangles (0,1,2) and (0,2,3), with per-vertex normals = the face normal.
std::shared_ptr<MeshData> quadMesh(const QuadCorners& corners, bool withNormals = true);

//! A planar, convex quad in double precision, for ray casting the expected result.
struct AnalyticQuad {
    QuadCorners corners;
    //! Ray (origin o, direction d) hit distance t > 0 inside the quad, if any.
    std::optional<double> intersect(const glm::dvec3& o, const glm::dvec3& d) const;
    glm::dvec3 normal() const;
};

//! Scene of the given quads, one grey material (albedo 0.5) and no lights.
Scene quadScene(const std::vector<AnalyticQuad>& quads, glm::vec3 albedo = glm::vec3(0.5f));
//! A floor square of half side `half` at y = 0, facing up (quadScene's material).
Scene floorScene(double half = 50.0);
//! A floor [-3, 3]^2 at y = 0 and a wall 2 high across it at z = -1, facing +z
//! (quadScene's material); `lit`: with a point light at (0.5, 1.5, 1), intensity 3. The
//! host-integration tests' corner, seen from (1, 2, 4).
Scene cornerScene(bool lit);
//! `scene` with a sun added: a directional light from above, (0.3, -1, 0.2), intensity 3
//! (the indirect-light tests' lit open plane).
Scene withSun(Scene scene);
//! `scene` with a horizontal disc of radius a at height h added: a 256-gon of the disc's area
//! (its edges' midpoints at a (1 - 2.5e-5), its corners at a (1 + 5e-5)), seen from both sides.
Scene withDisc(Scene scene, double a, double h);

//! Closed meshes (every edge on exactly two triangles, outward winding), indexed.
//! The unit cube [0, 1]^3: 8 vertices, 12 triangles.
std::shared_ptr<MeshData> cubeMesh();
//! The unit sphere as a subdivided icosahedron (20 * 4^subdivisions triangles).
std::shared_ptr<MeshData> icosphereMesh(int subdivisions);
//! A scene of one mesh with the given transform and a grey material.
Scene singleMeshScene(std::shared_ptr<const MeshData> mesh, const glm::mat4& model = glm::mat4(1.0f));

//! The camera the host-buffer tests look into the Cornell box with: from (278, 273, -700)
//! at its back wall, 40 degrees vertical field of view, near 10, far 5000.
Camera cornellCamera(int width, int height);

//! Ray through the centre of pixel (x, y) of a width x height image (row 0 at the top),
//! in view space, computed in double from the camera's float projection matrix.
struct ViewRay {
    glm::dvec3 origin;
    glm::dvec3 direction;
};
ViewRay pixelRay(const Camera& camera, int x, int y, int width, int height);
//! NDC of the centre of pixel (x, y), row 0 at the top.
glm::dvec2 pixelNdc(int x, int y, int width, int height);
//! Relative precision of half-float storage (11-bit significand): one ulp, 2^-10. Rounding to
//! nearest would give half of it, but the rounding of float to half is the implementation's
//! (NVIDIA 580 rounds toward zero: its error was 1.13 times the half-ulp bound).
inline constexpr double kHalfRelative = 1.0 / 1024.0;
//! The first three channels of pixel (x, y).
glm::dvec3 texel3(const Image& image, int x, int y);
//! The world point of pixel (x, y) of view-space positions (GBuffer::readPositions), through
//! the inverse view matrix `toWorld`.
glm::dvec3 worldPoint(const Image& viewPositions, const glm::dmat4& toWorld, int x, int y);

} // namespace obscura::test
