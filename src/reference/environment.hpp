#pragma once
// An equirectangular environment with luminance importance sampling.
//
// Direction convention: pixel column u in [0,1) and row v in [0,1] (row 0 at the top) map to
// phi = 2 pi (u - 0.5) + rotation and theta = pi v, direction
// (sin theta sin phi, cos theta, -sin theta cos phi): +y is up and the image centre looks
// down -z. Negative texels (left by lossy EXR compression) count as 0; NaN or infinite
// texels are refused.
#include "obscura/scene.hpp"
#include "obscura/texture.hpp"

#include <glm/glm.hpp>

#include <cstdint>
#include <vector>

namespace obscura::reference::detail {

class EnvironmentMap {
public:
    //! Throws Error{Io} when the file cannot be read, Error{InvalidArgument} for an empty or
    //! non-finite image.
    explicit EnvironmentMap(const Environment& env);

    //! Radiance arriving from direction `w` (travelling toward the origin), W/(sr m^2).
    glm::dvec3 radiance(const glm::dvec3& w) const;
    //! A direction drawn proportionally to luminance x sin(theta), with its solid-angle pdf.
    glm::dvec3 sample(const glm::dvec2& u, double& pdf) const;
    double pdf(const glm::dvec3& w) const;
    //! A hash of the texels as loaded (with intensity): references key their caches on it.
    std::uint64_t contentHash() const;

private:
    glm::dvec2 toUv(const glm::dvec3& w) const;
    glm::dvec3 fromUv(const glm::dvec2& uv) const;

    int width_ = 0, height_ = 0;
    double intensity_ = 1.0, rotation_ = 0.0;
    std::vector<glm::dvec3> texels_;
    std::vector<double> marginal_;    //!< cumulative over rows, height + 1 entries
    std::vector<double> conditional_; //!< cumulative over each row, (width + 1) per row
    double total_ = 0.0;
};

} // namespace obscura::reference::detail
