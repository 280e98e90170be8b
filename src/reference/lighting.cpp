// Direct light with visibility, one-bounce indirect light, shadows and image-based light.
#include "obscura/error.hpp"
#include "reference/estimators.hpp"

#include <cmath>
#include <string>

namespace obscura::reference::detail {
namespace {

// Irradiance from one light at a receiver (position x, geometric normal ng for the horizon
// and ray offsets, shading normal ns for the cosine), and the same without visibility.
// Area lights use one sample `u` per call; hard lights are exact.
struct LightSample {
    glm::dvec3 irradiance{0.0}; //!< with visibility
    glm::dvec3 unoccluded{0.0};
};

// Distance along unit d from o to the sphere (c, r), or infinity.
double sphereHit(const glm::dvec3& o, const glm::dvec3& d, const glm::dvec3& c, double r) {
    const glm::dvec3 oc = o - c;
    const double b = glm::dot(oc, d), q = glm::dot(oc, oc) - r * r, disc = b * b - q;
    if (disc < 0.0) return kInfinity;
    const double s = std::sqrt(disc), t0 = -b - s, t1 = -b + s;
    return t0 > 0.0 ? t0 : (t1 > 0.0 ? t1 : kInfinity);
}

class LightSampler {
public:
    LightSampler(const RayScene::Impl& scene, bool visibility) : scene_(scene), visibility_(visibility) {}

    //! `offset`: the least lift of shadow-ray origins off x (see offsetOrigin).
    LightSample sample(const Light& l, const glm::dvec3& x, const glm::dvec3& ng, const glm::dvec3& ns,
                       const glm::dvec2& u, double offset, std::uint64_t& rays) const {
        const glm::vec3 origin = offsetOrigin(x, ng, std::max(offset, scene_.floatError));
        const glm::dvec3 radiance = glm::dvec3(l.color) * static_cast<double>(l.intensity);
        switch (l.type) {
        case LightType::Directional: {
            const glm::dvec3 w = -glm::normalize(glm::dvec3(l.direction));
            return hard(radiance * std::max(0.0, glm::dot(ns, w)), ng, w, origin, nullptr, rays);
        }
        case LightType::Point:
        case LightType::Spot: {
            const glm::dvec3 toLight = glm::dvec3(l.position) - x;
            const double d2 = glm::dot(toLight, toLight);
            if (!(d2 > 0.0)) return {};
            const double d = std::sqrt(d2);
            const glm::dvec3 w = toLight / d;
            const double r = l.radius;
            double falloff = 1.0 / std::max(d2, r * r);
            if (l.type == LightType::Spot)
                falloff *= spotCone(glm::dot(-w, glm::normalize(glm::dvec3(l.direction))), std::cos(double(l.innerAngle)),
                                    std::cos(double(l.outerAngle)));
            const glm::dvec3 target(l.position);
            return hard(radiance * (falloff * std::max(0.0, glm::dot(ns, w))), ng, w, origin, &target, rays);
        }
        case LightType::Rect: return rect(l, radiance, x, ng, ns, origin, u, rays);
        case LightType::Sphere: return sphere(l, radiance, x, ng, ns, origin, u, rays);
        }
        return {};
    }

private:
    // Shadow rays run from the lifted origin to the light, stopping 2^-16 of the way short of
    // it: a light that lies on geometry (an emitter modelled both as a mesh and as a light)
    // must not shadow itself. Distant lights (target = nullptr) run to infinity.
    LightSample hard(const glm::dvec3& e, const glm::dvec3& ng, const glm::dvec3& w, const glm::vec3& origin,
                     const glm::dvec3* target, std::uint64_t& rays) const {
        if (glm::dot(ng, w) <= 0.0 || e == glm::dvec3(0.0)) return {};
        LightSample s{e, e};
        if (!visibility_) return s;
        glm::dvec3 dir = w;
        double distance = kInfinity;
        if (target) {
            const glm::dvec3 toLight = *target - glm::dvec3(origin);
            distance = glm::length(toLight);
            if (!(distance > 0.0)) return s;
            dir = toLight / distance;
            distance *= 1.0 - std::ldexp(1.0, -16);
        }
        ++rays;
        if (scene_.occluded(origin, dir, distance)) s.irradiance = glm::dvec3(0.0);
        return s;
    }

    // Uniform area sampling of the rectangle: E = L A cos(x) cos(light) / d^2.
    LightSample rect(const Light& l, const glm::dvec3& radiance, const glm::dvec3& x, const glm::dvec3& ng,
                     const glm::dvec3& ns, const glm::vec3& origin, const glm::dvec2& u, std::uint64_t& rays) const {
        const glm::dvec3 n = glm::normalize(glm::dvec3(l.direction));
        const glm::dvec3 t = glm::normalize(glm::dvec3(l.tangent) - glm::dot(glm::dvec3(l.tangent), n) * n);
        const glm::dvec3 b = glm::cross(n, t);
        const glm::dvec3 q = glm::dvec3(l.position) + (u.x - 0.5) * double(l.size.x) * t + (u.y - 0.5) * double(l.size.y) * b;
        const glm::dvec3 toLight = q - x;
        const double d2 = glm::dot(toLight, toLight);
        if (!(d2 > 0.0)) return {};
        const glm::dvec3 w = toLight / std::sqrt(d2);
        const double cosLight = glm::dot(n, -w);
        if (cosLight <= 0.0) return {};
        const double area = double(l.size.x) * l.size.y;
        return hard(radiance * (area * cosLight * std::max(0.0, glm::dot(ns, w)) / d2), ng, w, origin, &q, rays);
    }

    // Uniform sampling of the cone the sphere subtends: E = L cos / pdf.
    LightSample sphere(const Light& l, const glm::dvec3& radiance, const glm::dvec3& x, const glm::dvec3& ng,
                       const glm::dvec3& ns, const glm::vec3& origin, const glm::dvec2& u, std::uint64_t& rays) const {
        const glm::dvec3 c(l.position);
        const double r = l.radius, d = glm::length(c - x);
        if (!(d > r)) return {radiance * kPi, radiance * kPi}; // inside the emitter: radiance from everywhere
        // 1 - cos(half-angle) = x / (1 + sqrt(1 - x)), x = (r/d)^2: no cancellation for tiny spheres.
        const double s2 = (r / d) * (r / d), oneMinusCos = s2 / (1.0 + std::sqrt(std::max(0.0, 1.0 - s2)));
        const glm::dvec3 w = toWorld(uniformCone(u, oneMinusCos), (c - x) / d);
        const double pdf = 1.0 / (2.0 * kPi * oneMinusCos);
        const double distance = sphereHit(x, w, c, r);
        if (std::isinf(distance)) return {};
        const glm::dvec3 onSphere = x + distance * w;
        return hard(radiance * (std::max(0.0, glm::dot(ns, w)) / pdf), ng, w, origin, &onSphere, rays);
    }

    const RayScene::Impl& scene_;
    bool visibility_;
};

// Direct radiance at a surface point: emission + (albedo / pi) sum of light irradiance.
glm::dvec3 directRadiance(const LightSampler& lights, const Scene& scene, const glm::dvec3& x, const glm::dvec3& ng,
                          const glm::dvec3& ns, const glm::dvec3& albedo, const glm::dvec3& emission, const glm::dvec2& u,
                          double offset, std::uint64_t& rays) {
    glm::dvec3 e(0.0);
    for (const Light& l : scene.lights) e += lights.sample(l, x, ng, ns, u, offset, rays).irradiance;
    return emission + albedo / kPi * e;
}

bool isArea(const Light& l) { return l.type == LightType::Rect || l.type == LightType::Sphere; }

Estimator direct(const RayScene::Impl& scene, const DirectLight& q) {
    const bool anyArea = std::any_of(scene.scene.lights.begin(), scene.scene.lights.end(), isArea);
    return [&scene, q, anyArea](const ShadingPoint& p, int n, PixelSampler& s, std::uint64_t& rays) {
        const LightSampler lights(scene, q.visibility);
        // Hard lights give the same value every sample: one sample is exact.
        const int count = anyArea ? n : 1;
        glm::dvec3 sum(0.0);
        for (int i = 0; i < count; ++i)
            sum += directRadiance(lights, scene.scene, p.position, p.normal, p.shadingNormal, p.albedo, p.emission,
                                  s.lightPoint(static_cast<std::uint32_t>(i)), p.uncertainty, rays);
        return glm::dvec4(sum / double(count), 0.0);
    };
}

// One sample of each strategy (the cosine and the environment's luminance) of the irradiance
// E = Integral L_env(w) V(w) (n.w) dw at a point leaving `origin` with normal n, combined by
// the balance heuristic: f / (p_cosine + p_env) each. V: no occluder within `radius`.
glm::dvec3 environmentIrradianceSample(const RayScene::Impl& scene, const glm::vec3& origin, const glm::dvec3& n,
                                       bool visibility, double radius, const glm::dvec2& uCosine,
                                       const glm::dvec2& uEnvironment, std::uint64_t& rays) {
    const auto& env = *scene.environment;
    const auto contribution = [&](const glm::dvec3& w) {
        const double c = glm::dot(n, w);
        if (c <= 0.0) return glm::dvec3(0.0);
        if (visibility) {
            ++rays;
            if (scene.occluded(origin, w, radius)) return glm::dvec3(0.0);
        }
        return env.radiance(w) * c / (c / kPi + env.pdf(w));
    };
    double pdf = 0.0;
    return contribution(toWorld(cosineHemisphere(uCosine), n)) + contribution(env.sample(uEnvironment, pdf));
}

Estimator indirect(const RayScene::Impl& scene, const IndirectLight& q) {
    if (!(q.radius > 0.0)) throw Error(ErrorCode::InvalidArgument, "IndirectLight::radius must be > 0 world units");
    if (q.environment && !scene.environment)
        throw Error(ErrorCode::InvalidArgument, "IndirectLight::environment needs Scene::environment");
    return [&scene, q](const ShadingPoint& p, int n, PixelSampler& s, std::uint64_t& rays) {
        const LightSampler lights(scene, q.directVisibility);
        const glm::vec3 origin = surfaceOrigin(scene, p);
        glm::dvec3 sum(0.0);
        for (int i = 0; i < n; ++i) {
            // Cosine sampling: (albedo/pi) L cos / (cos/pi) = albedo L.
            const glm::dvec3 w = toWorld(cosineHemisphere(s.point(static_cast<std::uint32_t>(i))), p.normal);
            ++rays;
            const auto hit = scene.intersect(origin, w, q.radius);
            if (!hit) continue;
            const glm::dvec3 y = glm::dvec3(origin) + hit->distance * w;
            const glm::dvec3 ng = glm::dot(hit->normal, w) > 0.0 ? -hit->normal : hit->normal;
            // The hit point carries the float error of its ray parameter. Its light sample must
            // be independent of the bounce direction (a second R2 stream with the same index
            // would only shift it), so it comes from the pixel's PCG stream.
            const double offset = std::ldexp(hit->distance + glm::length(glm::dvec3(origin)), -20);
            sum += directRadiance(lights, scene.scene, y, ng, scene.shadingNormal(*hit, ng), scene.albedo(*hit),
                                  scene.emission(*hit, -w), s.uniform2(), offset, rays);
            if (q.environment) {
                // The hit's own image-based light, one sample of each strategy, from a point
                // moved off the surface by the hit's error bound.
                const glm::vec3 from = offsetOrigin(y, ng, std::max(offset, scene.floatError));
                sum += scene.albedo(*hit) / kPi *
                       environmentIrradianceSample(scene, from, ng, true, kInfinity, s.uniform2(), s.uniform2(), rays);
            }
        }
        return glm::dvec4(p.albedo * sum / double(n), 0.0);
    };
}

Estimator shadow(const RayScene::Impl& scene, const Shadow& q) {
    if (q.light >= scene.scene.lights.size())
        throw Error(ErrorCode::InvalidArgument, "Shadow::light = " + std::to_string(q.light) + " but the scene has " +
                                                    std::to_string(scene.scene.lights.size()) + " lights");
    const Light light = scene.scene.lights[q.light];
    return [&scene, light](const ShadingPoint& p, int n, PixelSampler& s, std::uint64_t& rays) {
        const LightSampler lights(scene, true);
        const int count = isArea(light) ? n : 1;
        double visible = 0.0, total = 0.0;
        for (int i = 0; i < count; ++i) {
            // The geometric normal for the cosine: shadows are a property of visibility.
            const LightSample ls = lights.sample(light, p.position, p.normal, p.normal,
                                                 s.lightPoint(static_cast<std::uint32_t>(i)), p.uncertainty, rays);
            visible += ls.irradiance.r + ls.irradiance.g + ls.irradiance.b;
            total += ls.unoccluded.r + ls.unoccluded.g + ls.unoccluded.b;
        }
        if (!(total > 0.0)) return glm::dvec4(0.0); // the light does not reach this side at all
        return glm::dvec4(visible / total, 1.0, 0.0, 0.0);
    };
}

Estimator imageBased(const RayScene::Impl& scene, const ImageBasedLight& q) {
    if (!scene.environment)
        throw Error(ErrorCode::InvalidArgument, "ImageBasedLight needs Scene::environment (an equirectangular HDR file)");
    if (!(q.radius > 0.0)) throw Error(ErrorCode::InvalidArgument, "ImageBasedLight::radius must be > 0 world units");
    return [&scene, q](const ShadingPoint& p, int n, PixelSampler& s, std::uint64_t& rays) {
        const glm::vec3 origin = surfaceOrigin(scene, p);
        const LightSampler lights(scene, q.visibility);
        glm::dvec3 e(0.0);
        for (int i = 0; i < n; ++i) {
            e += environmentIrradianceSample(scene, origin, p.normal, q.visibility, q.radius,
                                             s.point(static_cast<std::uint32_t>(i)),
                                             s.lightPoint(static_cast<std::uint32_t>(i)), rays);
            if (q.lights)
                for (const Light& l : scene.scene.lights)
                    e += lights.sample(l, p.position, p.normal, p.normal, s.uniform2(), p.uncertainty, rays).irradiance;
        }
        e /= double(n);
        return glm::dvec4(q.irradianceOnly ? e : p.albedo / kPi * e, 0.0);
    };
}

} // namespace

Estimator lightingEstimator(const RayScene::Impl& scene, const Quantity& quantity) {
    if (const auto* q = std::get_if<DirectLight>(&quantity)) return direct(scene, *q);
    if (const auto* q = std::get_if<IndirectLight>(&quantity)) return indirect(scene, *q);
    if (const auto* q = std::get_if<Shadow>(&quantity)) return shadow(scene, *q);
    return imageBased(scene, std::get<ImageBasedLight>(quantity));
}

} // namespace obscura::reference::detail
