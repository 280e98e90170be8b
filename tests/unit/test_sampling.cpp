// The sampling library's CPU mirror (src/core/sampling.hpp, the same formulas as
// shaders/common/sampling.glsl): sequences, hemisphere mappings and the tangent frame.
#include "core/sampling.hpp"
#include "frame_checks.hpp"

#include <catch2/catch.hpp>

#include <cmath>

using namespace obscura::detail;

TEST_CASE("Hammersley points are the base-2 radical inverse of the index", "[sampling]") {
    CHECK(radicalInverse2(0) == 0.0f);
    CHECK(radicalInverse2(1) == 0.5f);
    CHECK(radicalInverse2(2) == 0.25f);
    CHECK(radicalInverse2(3) == 0.75f);
    CHECK(radicalInverse2(6) == 0.375f);
    // 16 points: every 1/4 x 1/4 cell holds exactly one (a (0, 4, 2)-net in base 2).
    int cells[4][4] = {};
    for (std::uint32_t i = 0; i < 16; ++i) {
        const glm::vec2 u = hammersley(i, 16);
        ++cells[static_cast<int>(u.x * 4)][static_cast<int>(u.y * 4)];
    }
    for (auto& row : cells)
        for (int c : row) CHECK(c == 1);
}

TEST_CASE("The third Hammersley coordinate is the base-3 radical inverse and independent of the second", "[sampling]") {
    CHECK(radicalInverse3(0) == 0.0f);
    CHECK(radicalInverse3(1) == Approx(1.0 / 3.0).epsilon(1e-7));
    CHECK(radicalInverse3(2) == Approx(2.0 / 3.0).epsilon(1e-7));
    CHECK(radicalInverse3(3) == Approx(1.0 / 9.0).epsilon(1e-7));
    CHECK(radicalInverse3(5) == Approx(7.0 / 9.0).epsilon(1e-7)); // 5 = 12_3 -> 0.21_3
    CHECK(radicalInverse3(0xFFFFFFFFu) < 1.0f);
    // 3D Hammersley with n = 2^a 3^b points is a net in both pairs: every 1/2 x 1/3 cell of
    // (base 2, base 3) holds n / 6 points (at n = 36: 6 each).
    int cells[2][3] = {};
    for (std::uint32_t i = 0; i < 36; ++i) ++cells[static_cast<int>(radicalInverse2(i) * 2)][static_cast<int>(radicalInverse3(i) * 3)];
    for (auto& row : cells)
        for (int c : row) CHECK(c == 6);
}

TEST_CASE("Hemisphere mappings give unit directions with the expected moments", "[sampling]") {
    // Means over a 4096-point Hammersley set (exact to about 1/4096 for these smooth
    // integrands): cosine weighting E[z] = 2/3, uniform E[z] = 1/2, both E[x] = E[y] = 0.
    glm::dvec3 cosine(0.0), uniform(0.0);
    constexpr std::uint32_t n = 4096;
    for (std::uint32_t i = 0; i < n; ++i) {
        const glm::vec2 u = hammersley(i, n);
        const glm::vec3 c = cosineHemisphere(u), w = uniformHemisphere(u);
        CHECK(std::abs(glm::length(c) - 1.0f) < 1e-6f);
        CHECK(std::abs(glm::length(w) - 1.0f) < 1e-6f);
        CHECK(c.z >= 0.0f);
        CHECK(w.z >= 0.0f);
        cosine += glm::dvec3(c);
        uniform += glm::dvec3(w);
    }
    cosine /= double(n);
    uniform /= double(n);
    CHECK(cosine.z == Approx(2.0 / 3.0).margin(2e-3));
    CHECK(uniform.z == Approx(0.5).margin(2e-3));
    CHECK(std::abs(cosine.x) < 2e-3);
    CHECK(std::abs(uniform.y) < 2e-3);
}

TEST_CASE("The tangent frame is orthonormal for every normal including +z and -z", "[sampling]") {
    for (const glm::vec3& n : obscura::test::tangentFrameNormals()) {
        CAPTURE(n.x, n.y, n.z);
        glm::vec3 t, b;
        tangentFrame(n, t, b);
        obscura::test::checkTangentFrame(n, t, b);
    }
}

TEST_CASE("The tiled random texture holds distinct uniform values below 1", "[sampling]") {
    double sum = 0.0;
    std::size_t repeats = 0;
    glm::vec2 previous(-1.0f);
    for (int y = 0; y < 64; ++y)
        for (int x = 0; x < 64; ++x) {
            const glm::vec2 v = noiseTexel(x, y);
            CHECK(v.x >= 0.0f);
            CHECK(v.x < 1.0f);
            CHECK(v.y >= 0.0f);
            CHECK(v.y < 1.0f);
            repeats += v == previous;
            previous = v;
            sum += v.x + v.y;
        }
    CHECK(repeats == 0);
    // The mean of 8192 uniform values: 0.5 within 5 sigma = 5 / sqrt(12 * 8192).
    CHECK(std::abs(sum / 8192.0 - 0.5) < 5.0 / std::sqrt(12.0 * 8192.0));
}
