#pragma once
// Random numbers, low-discrepancy points and direction sampling for the reference.
#include <glm/glm.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>

namespace obscura::reference::detail {

constexpr double kPi = 3.14159265358979323846;

//! PCG32 (O'Neill): a small generator with independent streams.
class Pcg32 {
public:
    Pcg32(std::uint64_t seed, std::uint64_t stream) : inc_((stream << 1u) | 1u) {
        next();
        state_ += seed;
        next();
    }
    std::uint32_t next() {
        const std::uint64_t old = state_;
        state_ = old * 6364136223846793005ULL + inc_;
        const auto xorshifted = static_cast<std::uint32_t>(((old >> 18u) ^ old) >> 27u);
        const auto rot = static_cast<std::uint32_t>(old >> 59u);
        return (xorshifted >> rot) | (xorshifted << ((32u - rot) & 31u));
    }
    //! Uniform in [0, 1).
    double uniform() { return (static_cast<double>(next()) + 0.5) * (1.0 / 4294967296.0); }

private:
    std::uint64_t state_ = 0;
    std::uint64_t inc_;
};

//! SplitMix64 finalizer: turns structured (seed, pixel, half) tuples into stream seeds.
inline std::uint64_t mix64(std::uint64_t x) {
    x += 0x9E3779B97F4A7C15ULL;
    x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ULL;
    x = (x ^ (x >> 27)) * 0x94D049BB133111EBULL;
    return x ^ (x >> 31);
}

//! Point i of the R2 sequence (Roberts 2018) shifted by a random offset (Cranley-Patterson):
//! low discrepancy, and each point uniformly distributed, so estimates stay unbiased.
inline glm::dvec2 r2Point(std::uint32_t i, const glm::dvec2& shift) {
    constexpr double a1 = 0.7548776662466927, a2 = 0.5698402909980532; // 1/phi2, 1/phi2^2
    const double x = shift.x + a1 * (i + 1), y = shift.y + a2 * (i + 1);
    return {x - std::floor(x), y - std::floor(y)};
}

//! An orthonormal basis around unit n without a degenerate case (Duff et al. 2017).
inline void basis(const glm::dvec3& n, glm::dvec3& t, glm::dvec3& b) {
    const double sign = std::copysign(1.0, n.z);
    const double a = -1.0 / (sign + n.z);
    const double c = n.x * n.y * a;
    t = {1.0 + sign * n.x * n.x * a, sign * c, -sign * n.x};
    b = {c, sign + n.y * n.y * a, -n.y};
}

inline glm::dvec3 toWorld(const glm::dvec3& local, const glm::dvec3& n) {
    glm::dvec3 t, b;
    basis(n, t, b);
    return local.x * t + local.y * b + local.z * n;
}

//! Cosine-weighted direction about +z (Malley); pdf = cos / pi.
inline glm::dvec3 cosineHemisphere(const glm::dvec2& u) {
    const double r = std::sqrt(u.x), phi = 2.0 * kPi * u.y;
    return {r * std::cos(phi), r * std::sin(phi), std::sqrt(std::max(0.0, 1.0 - u.x))};
}

//! Uniform direction about +z; pdf = 1 / (2 pi).
inline glm::dvec3 uniformHemisphere(const glm::dvec2& u) {
    const double z = u.x, r = std::sqrt(std::max(0.0, 1.0 - z * z)), phi = 2.0 * kPi * u.y;
    return {r * std::cos(phi), r * std::sin(phi), z};
}

//! Uniform direction in the cone about +z with 1 - cos(half-angle) = oneMinusCosMax (given
//! directly, so tiny cones do not cancel to 0); pdf = 1 / (2 pi oneMinusCosMax).
inline glm::dvec3 uniformCone(const glm::dvec2& u, double oneMinusCosMax) {
    const double oneMinusZ = u.x * oneMinusCosMax;
    const double z = 1.0 - oneMinusZ, r = std::sqrt(std::max(0.0, oneMinusZ * (2.0 - oneMinusZ))), phi = 2.0 * kPi * u.y;
    return {r * std::cos(phi), r * std::sin(phi), z};
}

//! Lifts a ray origin off the surface along its normal by
//!   max(2^-20 |p|_inf, minimum):
//! 2^-20 is 8 float ulps of the point's largest coordinate, above the float error of a
//! point; `minimum` is the point's own known uncertainty (ShadingPoint::uncertainty: a ray
//! hit's or a depth buffer's). Both are relative to the data, so no epsilon in world units is
//! involved, and both stay far below a pixel's footprint.
inline glm::vec3 offsetOrigin(const glm::dvec3& p, const glm::dvec3& n, double minimum = 0.0) {
    const double magnitude = std::max({std::abs(p.x), std::abs(p.y), std::abs(p.z)});
    return glm::vec3(p + n * std::max(std::ldexp(magnitude, -20), minimum));
}

} // namespace obscura::reference::detail

namespace obscura::reference::detail {

//! The random numbers of one pixel's half: R2 points with a random shift for the main two
//! dimensions (stratified), a second shifted R2 stream for light samples, PCG32 for the rest.
class PixelSampler {
public:
    PixelSampler(std::uint64_t seed, std::uint64_t stream)
        : rng_(mix64(seed), stream), shift_(rng_.uniform(), rng_.uniform()), lightShift_(rng_.uniform(), rng_.uniform()) {}
    glm::dvec2 point(std::uint32_t i) const { return r2Point(i, shift_); }
    glm::dvec2 lightPoint(std::uint32_t i) const { return r2Point(i, lightShift_); }
    double uniform() { return rng_.uniform(); }
    glm::dvec2 uniform2() { return {rng_.uniform(), rng_.uniform()}; }

private:
    Pcg32 rng_;
    glm::dvec2 shift_, lightShift_;
};

} // namespace obscura::reference::detail
