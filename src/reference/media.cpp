// Single scattering in a medium box: homogeneous, height fog (exact transmittance) or a
// density grid (ratio tracking).
#include "obscura/error.hpp"
#include "reference/estimators.hpp"

#include <cmath>
#include <string>

namespace obscura::reference::detail {
namespace {

// Parametric interval [t0, t1] of the ray inside the box (empty when t0 >= t1).
bool boxInterval(const glm::dvec3& o, const glm::dvec3& d, const glm::dvec3& lo, const glm::dvec3& hi, double& t0, double& t1) {
    t0 = 0.0;
    t1 = kInfinity;
    for (int a = 0; a < 3; ++a) {
        if (d[a] == 0.0) {
            if (o[a] < lo[a] || o[a] > hi[a]) return false;
            continue;
        }
        double ta = (lo[a] - o[a]) / d[a], tb = (hi[a] - o[a]) / d[a];
        if (ta > tb) std::swap(ta, tb);
        t0 = std::max(t0, ta);
        t1 = std::min(t1, tb);
    }
    return t0 < t1;
}

// (1 - exp(-x)) / x for any x (1 at 0): the mean of exp over a step of exponent x.
double meanExp(double x) { return x == 0.0 ? 1.0 : -std::expm1(-x) / x; }

// Integral of the density along the segment from p toward unit w over `length` (Constant and
// Height: exact; the box clips it).
double densityIntegral(const Medium& m, const glm::dvec3& p, const glm::dvec3& w, double length) {
    double t0, t1;
    if (!boxInterval(p, w, glm::dvec3(m.boxMin), glm::dvec3(m.boxMax), t0, t1)) return 0.0;
    t1 = std::min(t1, length);
    if (!(t1 > t0)) return 0.0;
    if (m.density == MediumDensity::Constant) return t1 - t0;
    // exp(-k (y - y0)) along y = p.y + t w.y: its value at the segment's lower end times the
    // mean over its rise (no overflow whichever way the ray climbs).
    const double k = m.heightFalloff, ya = p.y + t0 * w.y - m.boxMin.y, yb = p.y + t1 * w.y - m.boxMin.y;
    return std::exp(-k * std::max(std::min(ya, yb), 0.0)) * (t1 - t0) * meanExp(k * std::abs(yb - ya));
}

// Transmittance per channel along the segment: exact for Constant and Height media; for a
// Grid, ratio tracking (Novak, Selle and Jarosz 2014) against the majorant max sigma_t times
// the grid's largest density: unbiased, each channel weighted by 1 - sigma_t,c d(x) / majorant.
// `maxDensity`: mediumMaxDensity(m), found once per medium (a grid's is a scan of its values).
glm::dvec3 transmittance(const Medium& m, double maxDensity, const glm::dvec3& p, const glm::dvec3& w, double length,
                         PixelSampler& s) {
    const glm::dvec3 sigmaT = glm::dvec3(m.scattering) + glm::dvec3(m.absorption);
    if (m.density != MediumDensity::Grid) return glm::exp(-sigmaT * densityIntegral(m, p, w, length));
    double t0, t1;
    if (!boxInterval(p, w, glm::dvec3(m.boxMin), glm::dvec3(m.boxMax), t0, t1)) return glm::dvec3(1.0);
    t1 = std::min(t1, length);
    const double majorant = std::max({sigmaT.x, sigmaT.y, sigmaT.z}) * maxDensity;
    if (!(t1 > t0) || !(majorant > 0.0)) return glm::dvec3(1.0);
    glm::dvec3 t(1.0);
    for (double at = t0;;) {
        at -= std::log1p(-s.uniform()) / majorant;
        if (at >= t1) break;
        t *= 1.0 - sigmaT * (mediumDensity(m, p + at * w) / majorant);
        if (t.x == 0.0 && t.y == 0.0 && t.z == 0.0) break;
    }
    return t;
}

// Truncated exponential distribution on [0, L] with rate s (uniform when s L is tiny).
struct Exponential {
    double rate, length;
    double sample(double u) const {
        if (rate * length < 1e-9) return u * length;
        return -std::log1p(u * std::expm1(-rate * length)) / rate;
    }
    double pdf(double t) const {
        if (rate * length < 1e-9) return 1.0 / length;
        return rate * std::exp(-rate * t) / -std::expm1(-rate * length);
    }
};

// Equiangular distribution (Kulla and Fajardo 2012) toward a point light on [t0, t1].
struct Equiangular {
    double delta, distance, thetaA, thetaB; // closest approach along the ray, its distance, angle range
    Equiangular(const glm::dvec3& o, const glm::dvec3& d, const glm::dvec3& light, double t0, double t1) {
        delta = glm::dot(light - o, d);
        distance = glm::length(o + delta * d - light);
        thetaA = std::atan2(t0 - delta, distance);
        thetaB = std::atan2(t1 - delta, distance);
    }
    bool valid() const { return distance > 0.0 && thetaB > thetaA; }
    double sample(double u) const { return delta + distance * std::tan(thetaA + u * (thetaB - thetaA)); }
    double pdf(double t) const {
        const double x = t - delta;
        return distance / ((thetaB - thetaA) * (distance * distance + x * x));
    }
};

// Where along the view ray to scatter: a mixture of the equiangular distribution toward the
// light (point and spot lights), one truncated exponential per colour channel (so that a
// channel with little extinction keeps a heavy enough tail when another is dense) and a
// uniform part (so the pdf is never 0 on the segment). One-sample MIS: the estimate divides
// by the mixture's pdf.
class DistanceMixture {
public:
    DistanceMixture(const Equiangular& eq, bool useEquiangular, const glm::dvec3& sigmaT, double t0, double t1)
        : eq_(eq), t0_(t0), length_(t1 - t0) {
        for (int c = 0; c < 3; ++c) exp_[c] = Exponential{sigmaT[c], length_};
        weightEq_ = useEquiangular ? 0.4 : 0.0;
        weightExp_ = (1.0 - weightEq_ - kWeightUniform) / 3.0;
    }
    double sample(const glm::dvec2& u) const {
        double pick = u.y;
        if (pick < weightEq_) return eq_.sample(u.x);
        pick -= weightEq_;
        for (int c = 0; c < 3; ++c) {
            if (pick < weightExp_) return t0_ + exp_[c].sample(u.x);
            pick -= weightExp_;
        }
        return t0_ + u.x * length_;
    }
    double pdf(double t) const {
        double p = kWeightUniform / length_;
        if (weightEq_ > 0.0) p += weightEq_ * eq_.pdf(t);
        for (const Exponential& e : exp_) p += weightExp_ * e.pdf(t - t0_);
        return p;
    }

private:
    static constexpr double kWeightUniform = 0.1;
    Equiangular eq_;
    double t0_, length_;
    Exponential exp_[3]{};
    double weightEq_ = 0.0, weightExp_ = 0.0;
};

} // namespace

Estimator scatteringEstimator(const RayScene::Impl& scene, const SingleScattering& q) {
    if (q.medium >= scene.scene.media.size())
        throw Error(ErrorCode::InvalidArgument, "SingleScattering::medium = " + std::to_string(q.medium) +
                                                    " but the scene has " + std::to_string(scene.scene.media.size()) +
                                                    " media");
    const Medium medium = scene.scene.media[q.medium];
    // Its box, coefficients, phase and anisotropy were checked when the RayScene was made
    // (validateScene).
    const double maxDensity = mediumMaxDensity(medium);
    return [&scene, q, medium, maxDensity](const ShadingPoint& p, int n, PixelSampler& s, std::uint64_t& rays) {
        const glm::dvec3 sigmaS(medium.scattering), sigmaT = sigmaS + glm::dvec3(medium.absorption);
        double t0, t1;
        if (!boxInterval(p.origin, p.direction, glm::dvec3(medium.boxMin), glm::dvec3(medium.boxMax), t0, t1))
            return glm::dvec4(0, 0, 0, 1);
        t1 = std::min(t1, p.distance);
        if (!(t1 > t0)) return glm::dvec4(0, 0, 0, 1);
        const glm::dvec3 entry = p.origin + t0 * p.direction;
        const glm::dvec3 viewT = transmittance(medium, maxDensity, entry, p.direction, t1 - t0, s);
        glm::dvec3 sum(0.0);
        for (const Light& l : scene.scene.lights) {
            if (l.type == LightType::Rect || l.type == LightType::Sphere) continue; // area lights: not in this quantity
            const bool distant = l.type == LightType::Directional;
            const Equiangular equiangular(p.origin, p.direction, glm::dvec3(l.position), t0, t1);
            const DistanceMixture mixture(equiangular, !distant && equiangular.valid(), sigmaT, t0, t1);
            const glm::dvec3 radiance = glm::dvec3(l.color) * double(l.intensity);
            for (int i = 0; i < n; ++i) {
                const double t = std::clamp(mixture.sample(s.point(static_cast<std::uint32_t>(i))), t0, t1);
                const double pdf = mixture.pdf(t);
                const glm::dvec3 x = p.origin + t * p.direction;
                glm::dvec3 w;
                double distance, falloff = 1.0;
                if (distant) {
                    w = -glm::normalize(glm::dvec3(l.direction));
                    distance = kInfinity;
                } else {
                    const glm::dvec3 toLight = glm::dvec3(l.position) - x;
                    distance = glm::length(toLight);
                    if (!(distance > 0.0)) continue;
                    w = toLight / distance;
                    falloff = 1.0 / std::max(distance * distance, double(l.radius) * l.radius);
                    if (l.type == LightType::Spot)
                        falloff *= spotCone(glm::dot(-w, glm::normalize(glm::dvec3(l.direction))),
                                            std::cos(double(l.innerAngle)), std::cos(double(l.outerAngle)));
                }
                if (falloff == 0.0) continue;
                if (q.shadows) {
                    // Stop short of the light, as surface shadow rays do (lights placed on geometry).
                    ++rays;
                    if (scene.occluded(glm::vec3(x), w, distance * (1.0 - std::ldexp(1.0, -16)))) continue;
                }
                // Phase angle: between the light's travel direction (-w) and the direction toward the camera.
                const double phase = phaseFunction(medium.phase, medium.anisotropy, glm::dot(-w, -p.direction));
                const double density = mediumDensity(medium, x);
                if (density == 0.0) continue;
                const glm::dvec3 toLightT = transmittance(medium, maxDensity, x, w, distance, s);
                const glm::dvec3 viewSideT = transmittance(medium, maxDensity, entry, p.direction, t - t0, s);
                sum += sigmaS * density * viewSideT * phase * radiance * falloff * toLightT / pdf;
            }
        }
        return glm::dvec4(sum / double(n), (viewT.r + viewT.g + viewT.b) / 3.0);
    };
}

} // namespace obscura::reference::detail
