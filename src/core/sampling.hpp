#pragma once
// The CPU mirror of shaders/common/sampling.glsl (same formulas), for tests and for the
// content of the tiled random texture.
#include <glm/glm.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace obscura::detail {

inline float radicalInverse2(std::uint32_t i) {
    i = (i << 16) | (i >> 16);
    i = ((i & 0x00FF00FFu) << 8) | ((i & 0xFF00FF00u) >> 8);
    i = ((i & 0x0F0F0F0Fu) << 4) | ((i & 0xF0F0F0F0u) >> 4);
    i = ((i & 0x33333333u) << 2) | ((i & 0xCCCCCCCCu) >> 2);
    i = ((i & 0x55555555u) << 1) | ((i & 0xAAAAAAAAu) >> 1);
    return static_cast<float>(i) * 2.3283064365386963e-10f;
}

inline float radicalInverse3(std::uint32_t i) {
    std::uint32_t mirrored = 0, scale = 1;
    for (; i > 0 && scale < 1162261467u; i /= 3) {
        mirrored = mirrored * 3 + i % 3;
        scale *= 3;
    }
    return std::min(static_cast<float>(mirrored) / static_cast<float>(scale), 0.99999994f);
}

inline glm::vec2 hammersley(std::uint32_t i, std::uint32_t n) {
    return {static_cast<float>(i) / static_cast<float>(n), radicalInverse2(i)};
}

inline glm::vec3 cosineHemisphere(glm::vec2 u) {
    const float r = std::sqrt(u.x), phi = 6.28318530717958647692f * u.y;
    return {r * std::cos(phi), r * std::sin(phi), std::sqrt(std::max(1.0f - u.x, 0.0f))};
}

inline glm::vec3 uniformHemisphere(glm::vec2 u) {
    const float z = u.x, r = std::sqrt(std::max(1.0f - z * z, 0.0f)), phi = 6.28318530717958647692f * u.y;
    return {r * std::cos(phi), r * std::sin(phi), z};
}

inline void tangentFrame(const glm::vec3& n, glm::vec3& t, glm::vec3& b) {
    const float s = n.z >= 0.0f ? 1.0f : -1.0f;
    const float a = -1.0f / (s + n.z);
    const float c = n.x * n.y * a;
    t = {1.0f + s * n.x * n.x * a, s * c, -s * n.x};
    b = {c, s + n.y * n.y * a, -n.y};
}

//! Texel (x, y) of the tiled random texture: two uniform values in [0, 1) from a
//! PCG-style integer hash, so the texture is the same on every run and machine.
inline glm::vec2 noiseTexel(int x, int y) {
    const auto hash = [](std::uint32_t v) {
        v = v * 747796405u + 2891336453u;
        v = ((v >> ((v >> 28u) + 4u)) ^ v) * 277803737u;
        return (v >> 22u) ^ v;
    };
    const std::uint32_t h = hash(static_cast<std::uint32_t>(x) + 4099u * static_cast<std::uint32_t>(y));
    return {static_cast<float>(h >> 8) / 16777216.0f, static_cast<float>(hash(h) >> 8) / 16777216.0f};
}

} // namespace obscura::detail
