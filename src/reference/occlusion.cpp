// Ambient occlusion, obscurance and bent normals.
#include "obscura/error.hpp"
#include "core/validate.hpp"
#include "reference/estimators.hpp"

#include <cmath>

namespace obscura::reference {

double obscuranceWeight(ObscuranceFalloff falloff, double distance, double maxDistance) {
    if (!(distance < maxDistance)) return 1.0;
    const double t = std::max(0.0, distance / maxDistance);
    switch (falloff) {
    case ObscuranceFalloff::None: return 0.0;
    case ObscuranceFalloff::Linear: return t;
    case ObscuranceFalloff::Quadratic: return t * t;
    case ObscuranceFalloff::Smooth: return t * t * (3.0 - 2.0 * t);
    }
    return 1.0;
}

namespace detail {
namespace {

void requireRadius(double r, const char* what) {
    if (!(r > 0.0))
        throw Error(ErrorCode::InvalidArgument, std::string(what) + " must be > 0 world units (or infinite), got " +
                                                    std::to_string(r));
}

// Sample i of the pixel's set as a direction about `normal`, cosine-weighted or uniform.
glm::dvec3 hemisphereDirection(PixelSampler& s, int i, bool cosineWeighted, const glm::dvec3& normal) {
    const glm::dvec2 u = s.point(static_cast<std::uint32_t>(i));
    return toWorld(cosineWeighted ? cosineHemisphere(u) : uniformHemisphere(u), normal);
}

} // namespace

Estimator occlusionEstimator(const RayScene::Impl& scene, const Quantity& quantity) {
    if (const auto* ao = std::get_if<AmbientOcclusion>(&quantity)) {
        requireRadius(ao->radius, "AmbientOcclusion::radius");
        const AmbientOcclusion q = *ao;
        return [&scene, q](const ShadingPoint& p, int n, PixelSampler& s, std::uint64_t& rays) {
            const glm::vec3 origin = surfaceOrigin(scene, p);
            double visible = 0.0;
            for (int i = 0; i < n; ++i) {
                const glm::dvec3 w = hemisphereDirection(s, i, q.cosineWeighted, p.normal);
                ++rays;
                if (!scene.occluded(origin, w, q.radius)) visible += 1.0;
            }
            return glm::dvec4(visible / n, 0, 0, 0);
        };
    }
    if (const auto* ob = std::get_if<Obscurance>(&quantity)) {
        if (!(ob->maxDistance > 0.0) || std::isinf(ob->maxDistance))
            throw Error(ErrorCode::InvalidArgument, "Obscurance::maxDistance must be finite and > 0 world units");
        obscura::detail::requireEnumerator(ob->falloff,
                          {ObscuranceFalloff::None, ObscuranceFalloff::Linear, ObscuranceFalloff::Quadratic,
                           ObscuranceFalloff::Smooth},
                          "Obscurance::falloff");
        const Obscurance q = *ob;
        return [&scene, q](const ShadingPoint& p, int n, PixelSampler& s, std::uint64_t& rays) {
            const glm::vec3 origin = surfaceOrigin(scene, p);
            double sum = 0.0;
            for (int i = 0; i < n; ++i) {
                const glm::dvec3 w = hemisphereDirection(s, i, q.cosineWeighted, p.normal);
                ++rays;
                const auto hit = scene.intersect(origin, w, q.maxDistance);
                sum += hit ? obscuranceWeight(q.falloff, hit->distance, q.maxDistance) : 1.0;
            }
            return glm::dvec4(sum / n, 0, 0, 0);
        };
    }
    const BentNormal q = std::get<BentNormal>(quantity);
    requireRadius(q.radius, "BentNormal::radius");
    return [&scene, q](const ShadingPoint& p, int n, PixelSampler& s, std::uint64_t& rays) {
        const glm::vec3 origin = surfaceOrigin(scene, p);
        glm::dvec3 sum(0.0);
        for (int i = 0; i < n; ++i) {
            const glm::dvec3 w = toWorld(cosineHemisphere(s.point(static_cast<std::uint32_t>(i))), p.normal);
            ++rays;
            if (!scene.occluded(origin, w, q.radius)) sum += w;
        }
        const double len = glm::length(sum);
        return glm::dvec4(len > 0.0 ? sum / len : p.normal, 0.0);
    };
}

} // namespace detail
} // namespace obscura::reference
