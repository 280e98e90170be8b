#pragma once
// The tangent frame's checks, shared by its CPU mirror's unit test and the GLSL one's GPU test.
#include "core/sampling.hpp"

#include <catch2/catch.hpp>
#include <glm/glm.hpp>

#include <cmath>
#include <cstdint>
#include <vector>

namespace obscura::test {

//! Normals where a frame may break: (0, 0, +-1), signed zeros, just either side of the n.z = 0
//! seam, then 1000 more over the sphere.
inline std::vector<glm::vec3> tangentFrameNormals() {
    std::vector<glm::vec3> normals = {{0, 0, 1},   {0, 0, -1},          {-0.0f, -0.0f, -1}, {1, 0, -0.0f},
                                      {0, -1, 0},  {0, 1, -0.0f},       {1e-8f, 0, -1},     {0, -1e-8f, 1},
                                      glm::normalize(glm::vec3(1, 0, -1e-7f))};
    for (std::uint32_t i = 0; i < 1000; ++i) {
        const glm::vec3 d = detail::uniformHemisphere(detail::hammersley(i, 1000));
        normals.push_back(i % 2 ? d : -d);
    }
    return normals;
}

//! (t, b, n) finite, orthonormal and right-handed. 1e-5: each component takes a few float
//! operations (a few ulp, 2^-23 each, of values at most 1), far inside it.
inline void checkTangentFrame(const glm::vec3& n, const glm::vec3& t, const glm::vec3& b) {
    CHECK(std::isfinite(t.x + t.y + t.z + b.x + b.y + b.z));
    CHECK(std::abs(glm::dot(t, t) - 1.0f) < 1e-5f);
    CHECK(std::abs(glm::dot(b, b) - 1.0f) < 1e-5f);
    CHECK(std::abs(glm::dot(t, b)) < 1e-5f);
    CHECK(std::abs(glm::dot(t, n)) < 1e-5f);
    CHECK(std::abs(glm::dot(b, n)) < 1e-5f);
    CHECK(glm::dot(glm::cross(t, b), n) > 0.99999f); // right-handed
}

} // namespace obscura::test
