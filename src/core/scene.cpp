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
