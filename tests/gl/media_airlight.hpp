// The single-scattering integral of obscura/media.hpp in double precision for the media
// tests: media boxes of any density, point, spot and directional lights, no occluders, integrated by
// adaptive quadrature (tests/support/quadrature.hpp) along one world ray.
#pragma once
#include "quadrature.hpp"

#include "obscura/scene.hpp"

#include <glm/glm.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <span>

namespace obscura::test {

// [t0, t1] of ray o + t w inside the box, clipped to [0, end]; empty when t0 >= t1.
inline glm::dvec2 boxSpan(const Medium& m, glm::dvec3 o, glm::dvec3 w, double end) {
    double t0 = 0.0, t1 = end;
    for (int a = 0; a < 3; ++a) {
        if (w[a] == 0.0) {
            if (o[a] < m.boxMin[a] || o[a] > m.boxMax[a]) return {1.0, 0.0};
            continue;
        }
        double ta = (m.boxMin[a] - o[a]) / w[a], tb = (m.boxMax[a] - o[a]) / w[a];
        if (ta > tb) std::swap(ta, tb);
        t0 = std::max(t0, ta);
        t1 = std::min(t1, tb);
    }
    return {t0, t1};
}

// Optical depth of channel c from o along w over `length`: exact for constant media, 512
// midpoint samples of obscura::mediumDensity otherwise.
inline double opticalDepth(std::span<const Medium> media, glm::dvec3 o, glm::dvec3 w, double length, int c) {
    double tau = 0.0;
    for (const Medium& m : media) {
        const glm::dvec2 t = boxSpan(m, o, w, length);
        if (!(t.y > t.x)) continue;
        double integral = t.y - t.x;
        if (m.density != MediumDensity::Constant) {
            integral = 0.0;
            for (int i = 0; i < 512; ++i) integral += mediumDensity(m, o + (t.x + (t.y - t.x) * (i + 0.5) / 512) * w);
            integral *= (t.y - t.x) / 512;
        }
        tau += (double(m.scattering[c]) + m.absorption[c]) * integral;
    }
    return tau;
}

// In-scattered radiance of channel c along the world ray (unit w) up to `end` (Inf: none).
inline double airlight(std::span<const Medium> media, std::span<const Light> lights, glm::dvec3 o, glm::dvec3 w, double end,
                       int c, double relativeTolerance = 1e-7, int pieces = 256) {
    double first = std::numeric_limits<double>::infinity(), last = -first;
    for (const Medium& m : media) {
        const glm::dvec2 t = boxSpan(m, o, w, end);
        if (t.y > t.x) first = std::min(first, t.x), last = std::max(last, t.y);
    }
    if (!(last > first)) return 0.0;
    const auto f = [&](double t) {
        const glm::dvec3 x = o + t * w;
        double sum = 0.0;
        for (const Light& l : lights) {
            glm::dvec3 toLight;
            double distance = std::numeric_limits<double>::infinity(), falloff = 1.0;
            if (l.type == LightType::Directional) {
                toLight = -glm::normalize(glm::dvec3(l.direction));
            } else if (l.type == LightType::Point || l.type == LightType::Spot) {
                const glm::dvec3 d = glm::dvec3(l.position) - x;
                distance = glm::length(d);
                toLight = d / distance;
                falloff = 1.0 / std::max(distance * distance, double(l.radius) * l.radius);
                if (l.type == LightType::Spot) {
                    const double ci = std::cos(double(l.innerAngle)), co = std::cos(double(l.outerAngle));
                    const double s = std::clamp((glm::dot(-toLight, glm::normalize(glm::dvec3(l.direction))) - co) / (ci - co), 0.0, 1.0);
                    falloff *= s * s * (3 - 2 * s);
                }
            } else {
                continue;
            }
            double scatter = 0.0;
            for (const Medium& m : media) {
                const bool inside = glm::all(glm::greaterThanEqual(x, glm::dvec3(m.boxMin))) &&
                                    glm::all(glm::lessThanEqual(x, glm::dvec3(m.boxMax)));
                if (inside) scatter += m.scattering[c] * mediumDensity(m, x) * phaseFunction(m.phase, m.anisotropy, glm::dot(toLight, w));
            }
            sum += scatter * double(l.intensity) * l.color[c] * falloff * std::exp(-opticalDepth(media, x, toLight, distance, c));
        }
        return sum * std::exp(-opticalDepth(media, o, w, t, c));
    };
    return integrate(f, first, last, relativeTolerance, pieces);
}

} // namespace obscura::test
