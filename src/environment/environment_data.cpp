#include "environment/environment_data.hpp"

#include "obscura/error.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace obscura::detail {
namespace {

constexpr double kPi = std::numbers::pi;

double luminance(const glm::dvec3& c) { return 0.2126 * c.r + 0.7152 * c.g + 0.0722 * c.b; }

// The basis constants of the 9 functions (environment_bindings.h's order): 1, x, y, z, xy, yz,
// xz, 3y^2 - 1, x^2 - z^2 times these are orthonormal on the sphere.
std::array<double, 9> basisConstants() {
    const double k0 = 0.5 / std::sqrt(kPi), k1 = std::sqrt(3.0 / (4.0 * kPi)), k2 = std::sqrt(15.0 / (4.0 * kPi));
    return {k0, k1, k1, k1, k2, k2, k2, std::sqrt(5.0 / (16.0 * kPi)), std::sqrt(15.0 / (16.0 * kPi))};
}

// Integrals over mu = cos(theta) in [mu1, mu0] of 1, mu, mu^2, s, mu s (s = sqrt(1 - mu^2)).
struct RowIntegrals {
    double m0, m1, m2, s, muS;
};

RowIntegrals rowIntegrals(int y, int height) {
    const double mu0 = std::cos(kPi * y / height), mu1 = std::cos(kPi * (y + 1) / height);
    const auto fs = [](double mu) {
        const double s = std::sqrt(std::max(1.0 - mu * mu, 0.0));
        return 0.5 * (mu * s + std::asin(std::clamp(mu, -1.0, 1.0)));
    };
    const auto fmus = [](double mu) { return -std::pow(std::max(1.0 - mu * mu, 0.0), 1.5) / 3.0; };
    return {mu0 - mu1, 0.5 * (mu0 * mu0 - mu1 * mu1), (mu0 * mu0 * mu0 - mu1 * mu1 * mu1) / 3.0, fs(mu0) - fs(mu1),
            fmus(mu0) - fmus(mu1)};
}

// Integrals over phi in the column of 1, sin, cos, sin cos, cos 2phi.
struct ColumnIntegrals {
    double one, sin, cos, sinCos, cos2;
};

ColumnIntegrals columnIntegrals(int x, int width) {
    const double p0 = 2.0 * kPi * (double(x) / width - 0.5), p1 = 2.0 * kPi * (double(x + 1) / width - 0.5);
    const double s0 = std::sin(p0), s1 = std::sin(p1);
    return {p1 - p0, std::cos(p0) - std::cos(p1), s1 - s0, 0.5 * (s1 * s1 - s0 * s0),
            0.5 * (std::sin(2.0 * p1) - std::sin(2.0 * p0))};
}

} // namespace

glm::dvec3 equirectDirection(double u, double v) {
    const double phi = 2.0 * kPi * (u - 0.5), theta = kPi * v;
    return {std::sin(theta) * std::sin(phi), std::cos(theta), -std::sin(theta) * std::cos(phi)};
}

double texelSolidAngle(int y, int width, int height) {
    return 2.0 * kPi / width * (std::cos(kPi * y / height) - std::cos(kPi * (y + 1) / height));
}

Equirect cleanedEquirect(const Image& image, std::size_t& replaced) {
    if (image.width < 1 || image.height < 1 || image.channels < 1 ||
        image.pixels.size() < std::size_t(image.width) * std::size_t(image.height) * std::size_t(image.channels))
        throw Error(ErrorCode::InvalidArgument, "EnvironmentMap: the image is empty or smaller than its size says");
    Equirect env{image.width, image.height, {}};
    env.texels.resize(std::size_t(image.width) * std::size_t(image.height));
    replaced = 0;
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x) {
            glm::dvec3 c;
            bool bad = false;
            for (int k = 0; k < 3; ++k) {
                const double v = image.at(x, y, std::min(k, image.channels - 1));
                bad = bad || !std::isfinite(v) || v < 0.0;
                c[k] = std::isfinite(v) && v > 0.0 ? v : 0.0;
            }
            replaced += bad ? 1 : 0;
            env.at(x, y) = c;
        }
    return env;
}

std::optional<Sun> splitSun(Equirect& env, double threshold) {
    if (!(threshold > 0.0)) return std::nullopt;
    double total = 0.0;
    for (int y = 0; y < env.height; ++y) {
        const double dw = texelSolidAngle(y, env.width, env.height);
        for (int x = 0; x < env.width; ++x) total += luminance(env.at(x, y)) * dw;
    }
    const double limit = threshold * total / (4.0 * kPi);
    Sun sun;
    glm::dvec3 weighted(0.0);
    bool any = false;
    for (int y = 0; y < env.height; ++y) {
        const double dw = texelSolidAngle(y, env.width, env.height);
        for (int x = 0; x < env.width; ++x) {
            glm::dvec3& c = env.at(x, y);
            if (!(luminance(c) > limit)) continue;
            any = true;
            sun.irradiance += c * dw;
            weighted += luminance(c) * dw * equirectDirection((x + 0.5) / env.width, (y + 0.5) / env.height);
            c = glm::dvec3(0.0);
        }
    }
    if (!any) return std::nullopt;
    // Texels on opposite sides could cancel; then any direction of them is as good.
    const double len = glm::length(weighted);
    sun.towardSun = len > 0.0 ? weighted / len : glm::dvec3(0.0, 1.0, 0.0);
    return sun;
}

std::array<glm::dvec3, 9> projectSh(const Equirect& env) {
    std::vector<ColumnIntegrals> columns(std::size_t(env.width));
    for (int x = 0; x < env.width; ++x) columns[std::size_t(x)] = columnIntegrals(x, env.width);
    std::array<glm::dvec3, 9> c{};
    for (int y = 0; y < env.height; ++y) {
        const RowIntegrals r = rowIntegrals(y, env.height);
        const double s2 = r.m0 - r.m2; // the integral of s^2 = 1 - mu^2
        for (int x = 0; x < env.width; ++x) {
            const ColumnIntegrals& k = columns[std::size_t(x)];
            // x = s sin(phi), y = mu, z = -s cos(phi); x^2 - z^2 = -s^2 cos(2 phi).
            const double raw[9] = {r.m0 * k.one,       r.s * k.sin,    r.m1 * k.one,
                                   -r.s * k.cos,       r.muS * k.sin,  -r.muS * k.cos,
                                   -s2 * k.sinCos,     (3.0 * r.m2 - r.m0) * k.one, -s2 * k.cos2};
            const glm::dvec3& l = env.at(x, y);
            for (int i = 0; i < 9; ++i) c[std::size_t(i)] += l * raw[i];
        }
    }
    const auto k = basisConstants();
    for (int i = 0; i < 9; ++i) c[std::size_t(i)] *= k[std::size_t(i)];
    return c;
}

std::array<glm::dvec3, 9> irradianceShTerms(const std::array<glm::dvec3, 9>& coefficients, double window) {
    // A_l, the clamped cosine's convolution factors for bands 0, 1, 2 (Ramamoorthi and
    // Hanrahan 2001), and the window 1 / (1 + lambda l^2 (l + 1)^2).
    const double a[3] = {kPi, 2.0 * kPi / 3.0, kPi / 4.0};
    const double w[3] = {1.0, 1.0 / (1.0 + window * 4.0), 1.0 / (1.0 + window * 36.0)};
    const int band[9] = {0, 1, 1, 1, 2, 2, 2, 2, 2};
    const auto k = basisConstants();
    std::array<glm::dvec3, 9> terms{};
    for (int i = 0; i < 9; ++i)
        terms[std::size_t(i)] = coefficients[std::size_t(i)] * (a[band[i]] * w[band[i]] * k[std::size_t(i)]);
    return terms;
}

glm::dvec3 evaluateShTerms(const std::array<glm::dvec3, 9>& t, const glm::dvec3& n) {
    return t[0] + t[1] * n.x + t[2] * n.y + t[3] * n.z + t[4] * (n.x * n.y) + t[5] * (n.y * n.z) + t[6] * (n.x * n.z) +
           t[7] * (3.0 * n.y * n.y - 1.0) + t[8] * (n.x * n.x - n.z * n.z);
}

Equirect reducedEquirect(const Equirect& env, int width) {
    const int height = std::max(width / 2, 1);
    Equirect out{width, height, std::vector<glm::dvec3>(std::size_t(width) * std::size_t(height), glm::dvec3(0.0))};
    if (width >= env.width || height >= env.height) {
        // No smaller: each texel takes the source texel at its centre.
        for (int y = 0; y < height; ++y)
            for (int x = 0; x < width; ++x)
                out.at(x, y) = env.at(std::min(int((x + 0.5) / width * env.width), env.width - 1),
                                      std::min(int((y + 0.5) / height * env.height), env.height - 1));
        return out;
    }
    std::vector<double> weight(out.texels.size(), 0.0);
    for (int y = 0; y < env.height; ++y) {
        const double dw = texelSolidAngle(y, env.width, env.height);
        const int ty = std::min(int((y + 0.5) / env.height * height), height - 1);
        for (int x = 0; x < env.width; ++x) {
            const int tx = std::min(int((x + 0.5) / env.width * width), width - 1);
            const std::size_t i = std::size_t(ty) * std::size_t(width) + std::size_t(tx);
            out.texels[i] += env.at(x, y) * dw;
            weight[i] += dw;
        }
    }
    for (std::size_t i = 0; i < out.texels.size(); ++i)
        if (weight[i] > 0.0) out.texels[i] /= weight[i];
    return out;
}

glm::dvec3 convolvedIrradiance(const Equirect& reduced, const glm::dvec3& n) {
    glm::dvec3 sum(0.0);
    double weights = 0.0;
    for (int y = 0; y < reduced.height; ++y) {
        const double dw = texelSolidAngle(y, reduced.width, reduced.height);
        for (int x = 0; x < reduced.width; ++x) {
            const double c = glm::dot(n, equirectDirection((x + 0.5) / reduced.width, (y + 0.5) / reduced.height));
            if (c <= 0.0) continue;
            sum += reduced.at(x, y) * (c * dw);
            weights += c * dw;
        }
    }
    return weights > 0.0 ? sum * (kPi / weights) : glm::dvec3(0.0);
}

glm::dvec3 cubeTexelDirection(int face, int x, int y, int size) {
    const double s = 2.0 * (x + 0.5) / size - 1.0, t = 2.0 * (y + 0.5) / size - 1.0;
    glm::dvec3 d;
    switch (face) {
    case 0: d = {1.0, -t, -s}; break;
    case 1: d = {-1.0, -t, s}; break;
    case 2: d = {s, 1.0, t}; break;
    case 3: d = {s, -1.0, -t}; break;
    case 4: d = {s, -t, 1.0}; break;
    default: d = {-s, -t, -1.0}; break;
    }
    return glm::normalize(d);
}

std::vector<float> irradianceCube(const Equirect& reduced, int size) {
    std::vector<float> out(std::size_t(6) * std::size_t(size) * std::size_t(size) * 4);
    std::size_t i = 0;
    for (int face = 0; face < 6; ++face)
        for (int y = 0; y < size; ++y)
            for (int x = 0; x < size; ++x) {
                const glm::dvec3 e = convolvedIrradiance(reduced, cubeTexelDirection(face, x, y, size));
                out[i++] = float(e.r);
                out[i++] = float(e.g);
                out[i++] = float(e.b);
                out[i++] = 1.0f;
            }
    return out;
}

EnvironmentImportance importanceTable(const Equirect& reduced) {
    EnvironmentImportance table{reduced.width, reduced.height, std::vector<double>(reduced.texels.size())};
    double largest = 0.0;
    for (const auto& t : reduced.texels) largest = std::max(largest, luminance(t));
    const double floorLuminance = largest > 0.0 ? 1e-6 * largest : 1.0;
    double total = 0.0;
    for (int y = 0; y < reduced.height; ++y) {
        const double dw = table.solidAngle(y);
        for (int x = 0; x < reduced.width; ++x) {
            const std::size_t i = std::size_t(y) * std::size_t(reduced.width) + std::size_t(x);
            table.probability[i] = std::max(luminance(reduced.texels[i]), floorLuminance) * dw;
            total += table.probability[i];
        }
    }
    for (double& p : table.probability) p /= total;
    return table;
}

} // namespace obscura::detail
