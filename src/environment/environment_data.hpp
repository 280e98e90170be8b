#pragma once
// The CPU side of EnvironmentMap: the cleaned texels, the sun split, the SH projection, the
// reduced image with its convolution and importance table (all in double, in the
// environment's own frame). Kept apart from the GL code so that it is testable alone.
#include "obscura/environment.hpp"
#include "obscura/texture.hpp"

#include <glm/glm.hpp>

#include <array>
#include <cstddef>
#include <optional>
#include <vector>

namespace obscura::detail {

//! An equirectangular RGB image in double (row 0 at the zenith).
struct Equirect {
    int width = 0, height = 0;
    std::vector<glm::dvec3> texels;
    glm::dvec3& at(int x, int y) { return texels[std::size_t(y) * std::size_t(width) + std::size_t(x)]; }
    const glm::dvec3& at(int x, int y) const { return texels[std::size_t(y) * std::size_t(width) + std::size_t(x)]; }
};

//! The environment's direction at (u, v) in [0, 1]^2 (src/reference/environment.cpp's fromUv at rotation 0).
glm::dvec3 equirectDirection(double u, double v);
//! The solid angle of a texel of row y of an image of width x height texels.
double texelSolidAngle(int y, int width, int height);

//! `image` as RGB with NaN, infinite and negative channels set to 0; `replaced` counts the texels.
Equirect cleanedEquirect(const Image& image, std::size_t& replaced);

struct Sun {
    glm::dvec3 towardSun{0.0, 1.0, 0.0}; //!< unit, environment frame
    glm::dvec3 irradiance{0.0};          //!< on a surface facing it, W/m^2
};
//! Takes the texels brighter than threshold x the mean luminance (solid-angle weighted) out
//! of `env` as one sun; nothing when none is (or threshold <= 0).
std::optional<Sun> splitSun(Equirect& env, double threshold);

//! The exact projection of the piecewise-constant environment onto the 9 real SH basis
//! functions (environment_bindings.h's order, y up).
std::array<glm::dvec3, 9> projectSh(const Equirect& env);
//! The coefficients the lookup block holds: times A_l, the window and the basis constants.
std::array<glm::dvec3, 9> irradianceShTerms(const std::array<glm::dvec3, 9>& coefficients, double window);
//! E(n) from irradianceShTerms' terms, n in the environment's frame, not clamped.
glm::dvec3 evaluateShTerms(const std::array<glm::dvec3, 9>& terms, const glm::dvec3& n);

//! `env` reduced to width x width/2 texels by solid-angle-weighted area averages.
Equirect reducedEquirect(const Equirect& env, int width);
//! The convolved irradiance at the unit normal n (environment frame), cosine weights
//! normalized to integrate to pi.
glm::dvec3 convolvedIrradiance(const Equirect& reduced, const glm::dvec3& n);
//! The unit direction of texel (x, y) of face `face` of a cube of `size` texels (GL's faces).
glm::dvec3 cubeTexelDirection(int face, int x, int y, int size);
//! The convolved irradiance cube's faces, RGBA float, face after face.
std::vector<float> irradianceCube(const Equirect& reduced, int size);

EnvironmentImportance importanceTable(const Equirect& reduced);

} // namespace obscura::detail
