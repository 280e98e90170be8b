#include "obscura/scene.hpp"

#include "core/validate.hpp"

#include <cfloat>
#include <string>

#include <algorithm>
#include <cmath>

namespace obscura {
namespace {

using detail::requireFinite;
using detail::requireInRange;
using detail::requireEnumerator;
using detail::shortNumber;

void validateMeshData(const MeshData& d, const std::string& what) {
    const std::size_t n = d.positions.size();
    if (!d.normals.empty() && d.normals.size() != n)
        throw Error(ErrorCode::InvalidArgument, what + ": " + std::to_string(d.normals.size()) + " normals for " +
                                                    std::to_string(n) + " positions (need 0 or one per position)");
    if (!d.texcoords.empty() && d.texcoords.size() != n)
        throw Error(ErrorCode::InvalidArgument, what + ": " + std::to_string(d.texcoords.size()) + " texcoords for " +
                                                    std::to_string(n) + " positions (need 0 or one per position)");
    const std::size_t count = d.indices.empty() ? n : d.indices.size();
    if (count % 3 != 0)
        throw Error(ErrorCode::InvalidArgument, what + ": " + std::to_string(count) +
                                                    (d.indices.empty() ? " positions" : " indices") +
                                                    " is not a multiple of 3 (triangle list)");
    for (std::size_t i = 0; i < n; ++i)
        if (!detail::allFinite(d.positions[i]))
            throw Error(ErrorCode::InvalidArgument, what + ": position " + std::to_string(i) + " is NaN or Inf");
    for (std::size_t i = 0; i < d.indices.size(); ++i)
        if (d.indices[i] >= n)
            throw Error(ErrorCode::InvalidArgument, what + ": index " + std::to_string(i) + " = " +
                                                        std::to_string(d.indices[i]) + " >= " + std::to_string(n) +
                                                        " positions");
}

std::string lightName(std::size_t i) { return "Scene::lights[" + std::to_string(i) + "]"; }

void validateLight(const Light& l, std::size_t i) {
    const std::string what = lightName(i);
    requireEnumerator(l.type, {LightType::Point, LightType::Spot, LightType::Directional, LightType::Rect, LightType::Sphere},
                      what + ".type");
    requireFinite(l.color, what + ".color");
    requireFinite(l.position, what + ".position");
    requireFinite(l.direction, what + ".direction");
    const char* unit = l.type == LightType::Directional ? "W/m^2"
                       : (l.type == LightType::Rect || l.type == LightType::Sphere) ? "W/(sr m^2)"
                                                                                     : "W/sr";
    requireInRange(l.intensity, 0.0, FLT_MAX, what + ".intensity", unit);
    if (glm::any(glm::lessThan(l.color, glm::vec3(0.0f))))
        throw Error(ErrorCode::InvalidArgument, what + ".color must be >= 0 per channel");
    requireInRange(l.radius, 0.0, FLT_MAX, what + ".radius", "world units");
    if (l.type != LightType::Point && !(glm::length(glm::dvec3(l.direction)) > 0.0))
        throw Error(ErrorCode::InvalidArgument, what + ".direction must be non-zero");
    for (int c = 0; c < 3; ++c)
        if (static_cast<double>(l.color[c]) * l.intensity > FLT_MAX)
            throw Error(ErrorCode::InvalidArgument, what + ": color * intensity exceeds the float range");
    if (l.type == LightType::Spot) {
        requireInRange(l.outerAngle, 1e-6, 1.5707963, what + ".outerAngle", "radians, (0, pi/2)");
        requireInRange(l.innerAngle, 0.0, l.outerAngle, what + ".innerAngle", "radians, [0, outerAngle]");
    }
    if (l.type == LightType::Sphere && !(l.radius > 0.0f))
        throw Error(ErrorCode::InvalidArgument, what + ".radius of a sphere light must be > 0 world units");
    if (l.type == LightType::Rect) {
        requireFinite(l.tangent, what + ".tangent");
        requireFinite(glm::vec3(l.size, 0.0f), what + ".size");
        if (!(l.size.x > 0.0f && l.size.y > 0.0f))
            throw Error(ErrorCode::InvalidArgument, what + ".size of a rect light must be > 0 world units");
        const glm::dvec3 n = glm::normalize(glm::dvec3(l.direction)), t(l.tangent);
        if (!(glm::length(t - glm::dot(t, n) * n) > 1e-6 * glm::length(t)))
            throw Error(ErrorCode::InvalidArgument, what + ".tangent must not be zero or parallel to direction");
    }
}

void validateMaterial(const Material& m, std::size_t i) {
    const std::string what = "Scene::materials[" + std::to_string(i) + "]";
    requireFinite(m.albedo, what + ".albedo");
    requireFinite(m.emission, what + ".emission");
    if (glm::any(glm::lessThan(m.albedo, glm::vec3(0.0f))) || glm::any(glm::greaterThan(m.albedo, glm::vec3(1.0f))))
        throw Error(ErrorCode::InvalidArgument, what + ".albedo must be in [0,1] per channel");
    if (glm::any(glm::lessThan(m.emission, glm::vec3(0.0f))))
        throw Error(ErrorCode::InvalidArgument, what + ".emission must be >= 0 per channel");
}

void validateEnvironment(const Environment& e) {
    requireInRange(e.intensity, 0.0, FLT_MAX, "Scene::environment.intensity", "(radiance scale)");
    requireFinite(e.rotation, "Scene::environment.rotation");
}

void validateMedium(const Medium& m, std::size_t i) {
    const std::string what = "Scene::media[" + std::to_string(i) + "]";
    requireFinite(m.boxMin, what + ".boxMin");
    requireFinite(m.boxMax, what + ".boxMax");
    requireFinite(m.scattering, what + ".scattering");
    requireFinite(m.absorption, what + ".absorption");
    if (glm::any(glm::lessThan(m.boxMax, m.boxMin)))
        throw Error(ErrorCode::InvalidArgument, what + ".boxMax must be >= boxMin on every axis");
    if (glm::any(glm::lessThan(m.scattering, glm::vec3(0.0f))) || glm::any(glm::lessThan(m.absorption, glm::vec3(0.0f))))
        throw Error(ErrorCode::InvalidArgument, what + ": scattering and absorption must be >= 0 per channel (1/world unit)");
    requireEnumerator(m.phase, {PhaseFunction::Isotropic, PhaseFunction::HenyeyGreenstein, PhaseFunction::Rayleigh,
                                PhaseFunction::Schlick},
                      what + ".phase");
    if (!(std::abs(m.anisotropy) < 1.0f))
        throw Error(ErrorCode::InvalidArgument, what + ".anisotropy must be in (-1, 1), got " + shortNumber(m.anisotropy));
    requireEnumerator(m.density, {MediumDensity::Constant, MediumDensity::Height, MediumDensity::Grid}, what + ".density");
    if (!(m.heightFalloff >= 0.0f && std::isfinite(m.heightFalloff)))
        throw Error(ErrorCode::InvalidArgument, what + ".heightFalloff must be finite and >= 0 (1/world unit), got " +
                                                    shortNumber(m.heightFalloff));
    if (m.density == MediumDensity::Grid) {
        if (!m.grid) throw Error(ErrorCode::InvalidArgument, what + ".grid is null but density is Grid");
        const glm::ivec3 n = m.grid->size;
        if (glm::any(glm::lessThan(n, glm::ivec3(1))) || glm::any(glm::greaterThan(n, glm::ivec3(1024))))
            throw Error(ErrorCode::InvalidArgument, what + ".grid->size must be in [1, 1024] per axis");
        if (m.grid->values.size() != std::size_t(n.x) * std::size_t(n.y) * std::size_t(n.z))
            throw Error(ErrorCode::InvalidArgument, what + ".grid->values must hold size.x * size.y * size.z values, has " +
                                                        std::to_string(m.grid->values.size()));
        for (float v : m.grid->values)
            if (!(v >= 0.0f && std::isfinite(v)))
                throw Error(ErrorCode::InvalidArgument, what + ".grid->values must be finite and >= 0, found " + shortNumber(v));
    }
}

// Trilinear interpolation of the grid at box-relative coordinates u in [0, 1]^3 (cell centres
// at (i + 0.5) / size; clamped at the faces).
double gridDensity(const DensityGrid& g, const glm::dvec3& u) {
    const glm::dvec3 at = glm::clamp(u * glm::dvec3(g.size) - 0.5, glm::dvec3(0.0), glm::dvec3(g.size - 1));
    const glm::ivec3 i0 = glm::min(glm::ivec3(glm::floor(at)), g.size - 1), i1 = glm::min(i0 + 1, g.size - 1);
    const glm::dvec3 f = at - glm::dvec3(i0);
    const auto v = [&](int x, int y, int z) {
        return double(g.values[(std::size_t(z) * std::size_t(g.size.y) + std::size_t(y)) * std::size_t(g.size.x) + std::size_t(x)]);
    };
    const double x00 = v(i0.x, i0.y, i0.z) * (1 - f.x) + v(i1.x, i0.y, i0.z) * f.x;
    const double x10 = v(i0.x, i1.y, i0.z) * (1 - f.x) + v(i1.x, i1.y, i0.z) * f.x;
    const double x01 = v(i0.x, i0.y, i1.z) * (1 - f.x) + v(i1.x, i0.y, i1.z) * f.x;
    const double x11 = v(i0.x, i1.y, i1.z) * (1 - f.x) + v(i1.x, i1.y, i1.z) * f.x;
    return (x00 * (1 - f.y) + x10 * f.y) * (1 - f.z) + (x01 * (1 - f.y) + x11 * f.y) * f.z;
}

// A hash of three lattice coordinates and a seed to [0, 1) (integer mixing, no state).
double latticeValue(int x, int y, int z, std::uint32_t seed) {
    std::uint32_t h = seed * 0x9E3779B9u ^ std::uint32_t(x) * 0x85EBCA6Bu ^ std::uint32_t(y) * 0xC2B2AE35u ^ std::uint32_t(z) * 0x27D4EB2Fu;
    h ^= h >> 15;
    h *= 0x2C1B3C6Du;
    h ^= h >> 12;
    h *= 0x297A2D39u;
    h ^= h >> 15;
    return double(h) / 4294967296.0;
}

} // namespace

void validateScene(const Scene& scene) {
    for (std::size_t i = 0; i < scene.lights.size(); ++i) validateLight(scene.lights[i], i);
    if (scene.environment) validateEnvironment(*scene.environment);
    for (std::size_t i = 0; i < scene.media.size(); ++i) validateMedium(scene.media[i], i);
    for (std::size_t i = 0; i < scene.materials.size(); ++i) validateMaterial(scene.materials[i], i);
    const auto checkMaterial = [&](std::uint32_t index, const std::string& what) {
        if (index >= scene.materials.size())
            throw Error(ErrorCode::InvalidArgument, what + ".material = " + std::to_string(index) + " but the scene has " +
                                                        std::to_string(scene.materials.size()) + " materials");
    };
    for (std::size_t i = 0; i < scene.meshes.size(); ++i) {
        const std::string what = "Scene::meshes[" + std::to_string(i) + "]";
        if (!scene.meshes[i].data) throw Error(ErrorCode::InvalidArgument, what + ".data is null");
        requireFinite(scene.meshes[i].model, what + ".model");
        checkMaterial(scene.meshes[i].material, what);
        validateMeshData(*scene.meshes[i].data, what);
    }
    for (std::size_t i = 0; i < scene.meshRefs.size(); ++i) {
        const std::string what = "Scene::meshRefs[" + std::to_string(i) + "]";
        requireFinite(scene.meshRefs[i].model, what + ".model");
        checkMaterial(scene.meshRefs[i].material, what);
    }
}


double schlickK(double g) {
    const double bound = 1.0 - (1.0 - std::abs(g)) * (1.0 - std::abs(g));
    return std::copysign(std::min(std::abs(1.55 * g - 0.55 * g * g * g), bound), g);
}

double phaseFunction(PhaseFunction phase, double g, double c) {
    constexpr double pi = 3.14159265358979323846;
    switch (phase) {
    case PhaseFunction::Isotropic: return 1.0 / (4.0 * pi);
    case PhaseFunction::Rayleigh: return 3.0 * (1.0 + c * c) / (16.0 * pi);
    case PhaseFunction::HenyeyGreenstein: {
        const double d = 1.0 + g * g - 2.0 * g * c;
        return (1.0 - g * g) / (4.0 * pi * d * std::sqrt(d));
    }
    case PhaseFunction::Schlick: {
        const double k = schlickK(g), d = 1.0 - k * c;
        return (1.0 - k * k) / (4.0 * pi * d * d);
    }
    }
    return 0.0;
}

double mediumDensity(const Medium& m, const glm::dvec3& p) {
    const glm::dvec3 lo(m.boxMin), hi(m.boxMax);
    if (glm::any(glm::lessThan(p, lo)) || glm::any(glm::greaterThan(p, hi))) return 0.0;
    switch (m.density) {
    case MediumDensity::Constant: return 1.0;
    case MediumDensity::Height: return std::exp(-double(m.heightFalloff) * (p.y - lo.y));
    case MediumDensity::Grid: {
        const glm::dvec3 extent = hi - lo;
        const glm::dvec3 u = glm::dvec3(extent.x > 0 ? (p.x - lo.x) / extent.x : 0.5, extent.y > 0 ? (p.y - lo.y) / extent.y : 0.5,
                                        extent.z > 0 ? (p.z - lo.z) / extent.z : 0.5);
        return m.grid ? gridDensity(*m.grid, u) : 0.0;
    }
    }
    return 0.0;
}

double mediumMaxDensity(const Medium& m) {
    if (m.density == MediumDensity::Grid) {
        double most = 0.0;
        if (m.grid)
            for (float v : m.grid->values) most = std::max(most, double(v));
        return most;
    }
    return 1.0; // Constant, and Height at its floor (boxMin.y)
}

DensityGrid noiseDensityGrid(glm::ivec3 size, std::uint32_t seed, int octaves) {
    DensityGrid g{size, std::vector<float>(std::size_t(size.x) * std::size_t(size.y) * std::size_t(size.z))};
    const auto smooth = [](double t) { return t * t * (3.0 - 2.0 * t); };
    std::size_t i = 0;
    for (int z = 0; z < size.z; ++z)
        for (int y = 0; y < size.y; ++y)
            for (int x = 0; x < size.x; ++x, ++i) {
                const glm::dvec3 u = (glm::dvec3(x, y, z) + 0.5) / glm::dvec3(size);
                double sum = 0.0, amplitude = 0.5, frequency = 4.0;
                for (int o = 0; o < octaves; ++o, amplitude *= 0.5, frequency *= 2.0) {
                    const glm::dvec3 p = u * frequency, c = glm::floor(p), f = p - c;
                    const glm::ivec3 k(c);
                    double v = 0.0;
                    for (int corner = 0; corner < 8; ++corner) {
                        const glm::ivec3 d(corner & 1, (corner >> 1) & 1, corner >> 2);
                        const double w = (d.x ? smooth(f.x) : 1 - smooth(f.x)) * (d.y ? smooth(f.y) : 1 - smooth(f.y)) *
                                         (d.z ? smooth(f.z) : 1 - smooth(f.z));
                        v += w * latticeValue(k.x + d.x, k.y + d.y, k.z + d.z, seed + std::uint32_t(o));
                    }
                    sum += amplitude * v;
                }
                // sum in [0, 1 - 2^-octaves): clumps and clear gaps.
                g.values[i] = float(std::max(0.0, 2.0 * sum - 0.5));
            }
    return g;
}

Bounds sceneBounds(const Scene& scene) {
    Bounds b;
    for (const Mesh& mesh : scene.meshes) {
        if (!mesh.data) continue;
        for (const glm::vec3& p : mesh.data->positions) {
            const glm::vec3 w = glm::vec3(mesh.model * glm::vec4(p, 1.0f));
            if (b.empty) {
                b.min = b.max = w;
                b.empty = false;
            } else {
                b.min = glm::min(b.min, w);
                b.max = glm::max(b.max, w);
            }
        }
    }
    return b;
}

} // namespace obscura
