#include "reference/environment.hpp"

#include "obscura/assets.hpp"
#include "obscura/error.hpp"
#include "reference/hash.hpp"
#include "reference/sampling.hpp"

#include <algorithm>
#include <cmath>

namespace obscura::reference::detail {
namespace {

double luminance(const glm::dvec3& c) { return 0.2126 * c.r + 0.7152 * c.g + 0.0722 * c.b; }

// Index i with cdf[i] <= x < cdf[i+1] in a non-decreasing array of n + 1 entries.
int findInterval(const double* cdf, int n, double x) {
    const double* it = std::upper_bound(cdf, cdf + n + 1, x);
    return std::clamp(static_cast<int>(it - cdf) - 1, 0, n - 1);
}

} // namespace

EnvironmentMap::EnvironmentMap(const Environment& env) : intensity_(env.intensity), rotation_(env.rotation) {
    const Image img = assets::readImage(env.path);
    if (img.width < 1 || img.height < 1 || img.channels < 1)
        throw Error(ErrorCode::InvalidArgument, "environment " + env.path + " is empty");
    width_ = img.width;
    height_ = img.height;
    texels_.resize(static_cast<std::size_t>(width_) * static_cast<std::size_t>(height_));
    for (int y = 0; y < height_; ++y)
        for (int x = 0; x < width_; ++x) {
            glm::dvec3 c;
            for (int k = 0; k < 3; ++k) c[k] = img.at(x, y, std::min(k, img.channels - 1));
            if (!std::isfinite(c.r + c.g + c.b))
                throw Error(ErrorCode::InvalidArgument, "environment " + env.path + " has a NaN or infinite texel");
            // Lossy EXR compression (DWA) leaves small negative values; radiance is >= 0.
            c = glm::max(c, glm::dvec3(0.0));
            texels_[static_cast<std::size_t>(y) * static_cast<std::size_t>(width_) + static_cast<std::size_t>(x)] = c * intensity_;
        }
    // Piecewise-constant 2D distribution of luminance x sin(theta) (the equirectangular
    // Jacobian), with a tiny floor so that every direction keeps a non-zero pdf.
    conditional_.assign(static_cast<std::size_t>(height_) * static_cast<std::size_t>(width_ + 1), 0.0);
    marginal_.assign(static_cast<std::size_t>(height_ + 1), 0.0);
    double maxWeight = 0.0;
    for (const auto& t : texels_) maxWeight = std::max(maxWeight, luminance(t));
    const double floorWeight = maxWeight > 0.0 ? 1e-6 * maxWeight : 1.0;
    for (int y = 0; y < height_; ++y) {
        const double sinTheta = std::sin(kPi * (y + 0.5) / height_);
        double* row = &conditional_[static_cast<std::size_t>(y) * static_cast<std::size_t>(width_ + 1)];
        for (int x = 0; x < width_; ++x)
            row[x + 1] = row[x] + (std::max(luminance(texels_[static_cast<std::size_t>(y) * width_ + x]), floorWeight)) * sinTheta;
        marginal_[static_cast<std::size_t>(y) + 1] = marginal_[static_cast<std::size_t>(y)] + row[width_];
    }
    total_ = marginal_.back();
}

std::uint64_t EnvironmentMap::contentHash() const {
    Hasher h;
    h.add(width_).add(height_).add(rotation_);
    h.bytes(texels_.data(), texels_.size() * sizeof(glm::dvec3));
    return h.value();
}

glm::dvec2 EnvironmentMap::toUv(const glm::dvec3& w) const {
    const double theta = std::acos(std::clamp(w.y, -1.0, 1.0));
    double phi = std::atan2(w.x, -w.z) - rotation_;
    double u = phi / (2.0 * kPi) + 0.5;
    u -= std::floor(u);
    return {u, theta / kPi};
}

glm::dvec3 EnvironmentMap::fromUv(const glm::dvec2& uv) const {
    const double phi = 2.0 * kPi * (uv.x - 0.5) + rotation_, theta = kPi * uv.y;
    return {std::sin(theta) * std::sin(phi), std::cos(theta), -std::sin(theta) * std::cos(phi)};
}

glm::dvec3 EnvironmentMap::radiance(const glm::dvec3& w) const {
    const glm::dvec2 uv = toUv(w);
    const int x = std::min(static_cast<int>(uv.x * width_), width_ - 1);
    const int y = std::min(static_cast<int>(uv.y * height_), height_ - 1);
    return texels_[static_cast<std::size_t>(y) * static_cast<std::size_t>(width_) + static_cast<std::size_t>(x)];
}

glm::dvec3 EnvironmentMap::sample(const glm::dvec2& u, double& pdfOut) const {
    const int y = findInterval(marginal_.data(), height_, u.y * total_);
    const double* row = &conditional_[static_cast<std::size_t>(y) * static_cast<std::size_t>(width_ + 1)];
    const int x = findInterval(row, width_, u.x * row[width_]);
    // Uniform within the texel, from the leftover of the two uniforms.
    const double fy = (u.y * total_ - marginal_[y]) / (marginal_[y + 1] - marginal_[y]);
    const double fx = (u.x * row[width_] - row[x]) / (row[x + 1] - row[x]);
    const glm::dvec2 uv((x + std::clamp(fx, 0.0, 1.0)) / width_, (y + std::clamp(fy, 0.0, 1.0)) / height_);
    const glm::dvec3 w = fromUv(uv);
    pdfOut = pdf(w);
    return w;
}

double EnvironmentMap::pdf(const glm::dvec3& w) const {
    const glm::dvec2 uv = toUv(w);
    const int x = std::min(static_cast<int>(uv.x * width_), width_ - 1);
    const int y = std::min(static_cast<int>(uv.y * height_), height_ - 1);
    const double* row = &conditional_[static_cast<std::size_t>(y) * static_cast<std::size_t>(width_ + 1)];
    const double p = (row[x + 1] - row[x]) / total_; // probability of the texel
    // Sampling is uniform in (u, v) inside a texel, so the solid-angle density follows the
    // direction's own sin(theta): d(omega) = 2 pi^2 sin(theta) du dv.
    const double sinTheta = std::sin(kPi * uv.y);
    const double jacobian = (2.0 * kPi / width_) * (kPi / height_) * sinTheta;
    return jacobian > 0.0 ? p / jacobian : 0.0;
}

} // namespace obscura::reference::detail
