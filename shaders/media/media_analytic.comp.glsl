// media.analytic: single scattering without shadows, per medium box and light, from the
// airlight integral's closed forms (Sun, Ramamoorthi, Narasimhan and Nayar 2005).
//
// Point and spot lights: over the view ray's segment [t0, t1] in the box, with x' the signed
// distance along the ray from the foot of the light's perpendicular (a = t0 - x_p, b = t1 - x_p),
// h the light's distance from the ray's line, d = sqrt(x'^2 + h^2):
//   L = sigma_s I Integral_a^b exp(-sigma_t (x' - a + d)) p cone / d^2 dx'
// (the light's path taken as all in the medium: exact for a light inside the box).
// With x' + d = h tan(xi) this is Sun et al.'s
//   (2 / h) exp(sigma_t a) Integral_{xi_a}^{xi_b} exp(-u tan xi) p cone dxi,   u = sigma_t h.
// QUADRATURE: `steps` intervals equal in phi = atan(x' / h) (the equiangular variable), each
// with its exact Integral dx'/d^2, the phase and cone at its middle, and the exact mean of the
// exponential over it (so a medium dense enough to decay within one interval stays exact).
// TABLE: the phase and the cone at the segment's point nearest the light, and the integral from
// the table of G(u, v) = Integral_v^{pi/2} exp(-u (tan xi - tan v)) dxi (the tail of Sun's
// F, scaled by exp(u tan v)):
//   L = sigma_s I p cone (2 / h) [exp(-sigma_t d_a) G(u, xi_a) - exp(-sigma_t (b - a + d_b)) G(u, xi_b)]
// Both exponents are <= 0: Sun's form exp(sigma_t d cos gamma) F(...) overflows in float once
// sigma_t d > 88 while its F difference underflows; this one never does. G is smooth and
// bounded (pi/2 - v at u = 0, cos^2 v / u for large u), so bilinear interpolation in float
// (texelFetch, not the sampler's fixed-point weights) keeps its error small (media.hpp states
// the bound); beyond the table's last u, three terms of its asymptotic series.
// A light of radius r: within r of its centre 1/r^2, as the reference (x' uniform intervals).
// Near the line (h < 0.1 |x'| over the whole segment, the light off it: gamma -> 0 or pi)
// both take `steps` nodes in w = 1 / |x'|, where 1/d^2 dx' = |x'|^2 / d^2 dw is smooth: no
// 0/0 from h -> 0. A light on the ray inside the segment with h = 0 is a true singularity
// (radius 0): the result saturates at the half-float maximum.
// Directional lights: T toward the light taken linear along the segment (exact while the
// ray exits the box through one face): sigma_s p E exp(-sigma_t l_0) len (1 - exp(-x)) / x.
//! Every permutation the module compiles (validated by glslangValidator at build time):
//! variant: QUADRATURE
//! variant: TABLE
#include "../common/depth.glsl"
#include "../gbuffer/gbuffer_bindings.h"
#include "../gbuffer/light_irradiance.glsl"
#include "media_common.glsl"

layout(local_size_x = MEDIA_WORKGROUP, local_size_y = MEDIA_WORKGROUP, local_size_z = 1) in;
layout(binding = MEDIA_DEPTH_UNIT) uniform sampler2D depthTexture;
#ifdef TABLE
layout(binding = MEDIA_TABLE_UNIT) uniform sampler2D tableTexture;
#endif
layout(binding = MEDIA_OUT_IMAGE, rgba16f) writeonly uniform image2D scatteringOut;
layout(binding = MEDIA_DEPTH_OUT_IMAGE, rgba16f) writeonly uniform image2D depthOut;

const float kNearLine = 0.1;

// The integrand's angular factor p(cos) cone at signed offset x' (distance d from the light).
float analyticAngular(int m, LightData light, float x, float d, vec3 foot, vec3 direction) {
    const float c = d > 0.0 ? -x / d : 1.0; // light travel direction . direction to the camera
    float cone = 1.0;
    if (int(light.type) == GBUFFER_LIGHT_SPOT)
        cone = spotCone(dot(safeNormalize(foot + x * direction - light.position, light.direction), light.direction),
                        light.cosInner, light.cosOuter);
    return mediaPhase(int(media.media[m].phase), media.media[m].g, c) * cone;
}

// One interval [x0, x1] of offsets: `geometry` = its Integral dx / d^2, times the angular
// factor at offset xm, times the mean over it of exp(-sigma_t e), e = x' - a + d taken linear
// between its ends (e never decreases along the ray: de/dx' = 1 + x'/d >= 0). The mean is
// exact for the exponential however dense the medium: an interval holding many e-folds
// still gives its integral, (1 - exp(-sigma_t de)) / (sigma_t de), not a point sample.
vec3 analyticInterval(int m, LightData light, vec3 sigmaT, float a, float h, float x0, float x1, float xm, float geometry,
                      vec3 foot, vec3 direction) {
    const float e0 = (x0 - a) + length(vec2(x0, h)), e1 = (x1 - a) + length(vec2(x1, h));
    return (geometry * analyticAngular(m, light, xm, length(vec2(xm, h)), foot, direction)) * exp(-sigmaT * e0) *
           oneMinusExpOverX(sigmaT * max(e1 - e0, 0.0));
}

// Near the line (a and b on one side of the foot, h << |x'|; a0 the segment's start, where
// the view side's exponent counts from): `steps` intervals uniform in w = 1/|x'|, where Integral dx'/d^2 = Integral |x'|^2 / d^2 dw is smooth (no 0/0 as h -> 0).
vec3 analyticNearLine(int m, LightData light, vec3 sigmaT, float a0, float a, float b, float h, vec3 foot, vec3 direction) {
    const float side = b > 0.0 ? 1.0 : -1.0;
    const float sFar = max(abs(a), abs(b));
    const float sNear = min(max(min(abs(a), abs(b)), max(light.radius, 1e-30 * sFar)), sFar);
    const float w0 = 1.0 / sFar, dw = (1.0 / sNear - w0) / float(media.steps);
    vec3 sum = vec3(0.0);
    for (int i = 0; i < media.steps; ++i) {
        const float sA = 1.0 / (w0 + float(i) * dw), sB = 1.0 / (w0 + float(i + 1) * dw);
        const float sM = 1.0 / (w0 + (float(i) + 0.5) * dw);
        const float geometry = dw * (sM * sM) / (sM * sM + h * h);
        // Offsets in the ray's order: from a toward b.
        const float x0 = side > 0.0 ? side * sB : side * sA, x1 = side > 0.0 ? side * sA : side * sB;
        sum += analyticInterval(m, light, sigmaT, a0, h, x0, x1, side * sM, geometry, foot, direction);
    }
    return sum;
}

#ifdef TABLE
// G(u, pi/2 - e) (src/media/airlight_table.hpp): the table's G / (e^2 / (e + u)) on columns
// u = tableMaxU t^4 and rows y = [e / (e + c)] / [(pi/2) / (pi/2 + c)], c = u + the first
// column's u, interpolated bilinearly in float, times e^2 / (e + u); past the last column,
// three terms of its asymptotic series.
float analyticG(float u, float e) {
    if (u > media.tableMaxU) {
        // Watson's lemma on Integral_0^inf exp(-u s) / (1 + (s + tan v)^2) ds, tan v = cot e.
        const float tanV = 1.0 / tan(max(e, 1e-30));
        const float c2 = 1.0 / (1.0 + tanV * tanV);
        return c2 / u - 2.0 * tanV * c2 * c2 / (u * u) + (6.0 * tanV * tanV - 2.0) * c2 * c2 * c2 / (u * u * u);
    }
    const float halfPi = 0.5 * OBSCURA_PI, n = float(media.tableSize.x - 1);
    e = clamp(e, 0.0, halfPi);
    const float c = u + media.tableMaxU / (n * n * n * n);
    const vec2 at = vec2(sqrt(sqrt(u / media.tableMaxU)), clamp((e / (e + c)) * ((halfPi + c) / halfPi), 0.0, 1.0)) * n;
    const ivec2 i0 = min(ivec2(floor(at)), media.tableSize - 2);
    const vec2 f = at - vec2(i0);
    const float g00 = texelFetch(tableTexture, i0, 0).r, g10 = texelFetch(tableTexture, i0 + ivec2(1, 0), 0).r;
    const float g01 = texelFetch(tableTexture, i0 + ivec2(0, 1), 0).r, g11 = texelFetch(tableTexture, i0 + ivec2(1, 1), 0).r;
    return mix(mix(g00, g10, f.x), mix(g01, g11, f.x), f.y) * (e > 0.0 ? e * e / (e + u) : 0.0);
}
#endif

// The airlight over the piece [a, b] of the segment that starts at a0 (offsets from the foot),
// where 1/max(d^2, r^2) is 1/d^2, per channel, before sigma_s I.
vec3 analyticPiece(int m, LightData light, float a0, float a, float b, float h, vec3 foot, vec3 direction) {
    const vec3 sigmaT = media.media[m].extinction;
    if (!(a < 0.0 && b > 0.0) && h < kNearLine * min(abs(a), abs(b)))
        return analyticNearLine(m, light, sigmaT, a0, a, b, h, foot, direction);
    // On the line with radius 0 the result saturates (the integral is infinite).
    const float hh = max(h, 1e-30);
    const float phiA = atan(a, hh), phiB = atan(b, hh);
#ifdef TABLE
    // The phase and the cone at the piece's point nearest the light (exact for an isotropic
    // medium and a point light, Sun et al.'s case).
    const float xNear = clamp(0.0, a, b);
    const float nearFactor = analyticAngular(m, light, xNear, length(vec2(xNear, hh)), foot, direction);
    // pi/2 - xi = (pi/2 - phi) / 2 = atan(h, x') / 2: no cancellation near pi/2.
    const float eA = 0.5 * atan(hh, a), eB = 0.5 * atan(hh, b);
    const float dA = length(vec2(a, hh)), dB = length(vec2(b, hh));
    // A grey medium (the same sigma_t in every channel) takes one channel's lookups.
    const bool grey = sigmaT.r == sigmaT.g && sigmaT.g == sigmaT.b;
    vec3 sum;
    for (int c = 0; c < (grey ? 1 : 3); ++c) {
        const float u = sigmaT[c] * hh;
        sum[c] = exp(-sigmaT[c] * ((a - a0) + dA)) * analyticG(u, eA) - exp(-sigmaT[c] * ((b - a0) + dB)) * analyticG(u, eB);
    }
    if (grey) sum = vec3(sum.r);
    return max(sum, vec3(0.0)) * (2.0 / hh) * nearFactor;
#else
    // Intervals equal in phi: each has Integral dx'/d^2 = dphi / h exactly.
    const float dPhi = (phiB - phiA) / float(media.steps);
    vec3 sum = vec3(0.0);
    for (int i = 0; i < media.steps; ++i) {
        const float p0 = phiA + float(i) * dPhi;
        // The ends exactly: tan near +-pi/2 of a rounded angle is far off.
        const float x0 = i == 0 ? a : hh * tan(p0), x1 = i + 1 == media.steps ? b : hh * tan(p0 + dPhi);
        sum += analyticInterval(m, light, sigmaT, a0, hh, x0, x1, hh * tan(p0 + 0.5 * dPhi), dPhi / hh, foot, direction);
    }
    return sum;
#endif
}

// One point or spot light's airlight over the segment [a, b] (offsets from the foot), per
// channel, before sigma_s I. A light of radius r gives 1/r^2 within r of its centre (the
// reference's 1/max(d^2, r^2)): where the ray passes that close (h < r), the piece
// |x'| < sqrt(r^2 - h^2) takes `steps` intervals uniform in x' with the exponential's exact
// mean, the pieces before and after it the forms above.
vec3 analyticPointLight(int m, LightData light, float a, float b, float h, vec3 foot, vec3 direction) {
    const float r = light.radius;
    if (!(h < r)) return analyticPiece(m, light, a, a, b, h, foot, direction);
    const float c = sqrt(max(r * r - h * h, 0.0));
    vec3 sum = vec3(0.0);
    if (a < -c) sum += analyticPiece(m, light, a, a, min(b, -c), h, foot, direction);
    if (b > c) sum += analyticPiece(m, light, a, max(a, c), b, h, foot, direction);
    const float lo = max(a, -c), hi = min(b, c);
    if (hi > lo) {
        const float dx = (hi - lo) / float(media.steps);
        for (int i = 0; i < media.steps; ++i) {
            const float x0 = lo + float(i) * dx;
            sum += analyticInterval(m, light, media.media[m].extinction, a, h, x0, x0 + dx, x0 + 0.5 * dx, dx / (r * r), foot,
                                    direction);
        }
    }
    return sum;
}

// A directional light over the segment [t0, t1] of world ray (ow, ww): T toward the light
// linear between the ends' (exact while one face bounds the box toward the light).
vec3 analyticDirectional(int m, LightData light, vec3 ow, vec3 ww, vec3 direction, float t0, float t1) {
    const vec3 sigmaT = media.media[m].extinction;
    const vec3 towardWorld = mediaDirectionToWorld(-light.direction);
    const float l0 = mediaBoxInterval(m, ow + t0 * ww, towardWorld, kFloatMax).y;
    const float l1 = mediaBoxInterval(m, ow + t1 * ww, towardWorld, kFloatMax).y;
    const float len = t1 - t0;
    const float phase = mediaPhase(int(media.media[m].phase), media.media[m].g, dot(-light.direction, direction));
    return light.radiance * phase * exp(-sigmaT * max(l0, 0.0)) * len *
           oneMinusExpOverX(max(sigmaT * (len + max(l1, 0.0) - max(l0, 0.0)), vec3(0.0)));
}

void main() {
    const ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(pixel, media.size))) return;
    const MediaRay r = mediaViewRay(pixel, texelFetch(depthTexture, pixel, 0).r);
    const vec3 ow = mediaToWorld(r.origin), ww = mediaDirectionToWorld(r.direction);
    vec3 radiance = vec3(0.0);
    for (int m = 0; m < media.mediumCount; ++m) {
        const vec2 t = mediaBoxInterval(m, ow, ww, r.end);
        if (!(t.y > t.x) || all(equal(media.media[m].scattering, vec3(0.0)))) continue;
        const vec3 before = exp(-mediaOpticalDepth(ow, ww, t.x)); // the media in front of this box
        vec3 sum = vec3(0.0);
        for (int i = 0; i < media.lightCount; ++i) {
            const LightData light = lights[i];
            const int type = int(light.type);
            if (type == GBUFFER_LIGHT_DIRECTIONAL) {
                sum += analyticDirectional(m, light, ow, ww, r.direction, t.x, t.y);
            } else if (type == GBUFFER_LIGHT_POINT || type == GBUFFER_LIGHT_SPOT) {
                const float xp = dot(light.position - r.origin, r.direction);
                const vec3 foot = r.origin + xp * r.direction;
                const float h = length(light.position - foot);
                // Bounded before the products: a singular light (radius 0 on the ray) saturates, and
                // a channel without scattering stays 0 instead of 0 * Inf.
                sum += light.radiance * min(analyticPointLight(m, light, t.x - xp, t.y - xp, h, foot, r.direction), vec3(kFloatMax));
            }
        }
        radiance += before * media.media[m].scattering * sum;
    }
    imageStore(scatteringOut, pixel, roundedToHalf(vec4(clampRadiance(radiance), 1.0)));
    imageStore(depthOut, pixel, mediaStoredDepth(mediaOpticalDepth(ow, ww, r.end)));
}
