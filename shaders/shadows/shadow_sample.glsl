// Shadow-map lookups for a mapped light (see obscura/shadow_maps.hpp): which map a receiver
// uses, the biased receiver, and the lit fraction of the filter's comparisons. Reads the
// ShadowParams records at SHADOW_LIGHTS_SSBO and the maps at SHADOW_MAP_UNIT; needs
// frame.glsl's block (view space is the frame's). FILTER: SHADOW_FILTER_* (Hard by default);
// Hard and Pcf compare the maps at SHADOW_MAP_UNIT (a nearest or linear comparison sampler),
// the moment filters read the prefiltered moments at SHADOW_MOMENTS_UNIT.
#include "../common/frame.glsl"
#include "../common/math.glsl"
#include "shadow_bindings.h"

#ifndef FILTER
#define FILTER SHADOW_FILTER_HARD
#endif

layout(std430, binding = SHADOW_LIGHTS_SSBO) readonly buffer ShadowLights {
    ShadowParams shadowLights[];
};
layout(binding = SHADOW_MAP_UNIT) uniform sampler2DArrayShadow shadowMaps;
#if FILTER == SHADOW_FILTER_PCSS
layout(binding = SHADOW_DEPTH_READ_UNIT) uniform sampler2DArray shadowDepths;
#endif
// Distance from the light (along the map's axis for cube faces and spots) of window depth d
// in map c (ShadowMapInfo::depthMapping).
float shadowDistance(int k, int c, float d) {
    const vec4 m = shadowLights[k].cascades[c].depthMapping; // a, b, near, far
    return shadowLights[k].cascades[c].projection > 0.5 ? m.y / max(d + m.x, 1e-30) : (m.y - d) / m.x;
}

#if SHADOW_FILTER_MOMENTS(FILTER)
layout(binding = SHADOW_MOMENTS_UNIT) uniform sampler2DArray shadowMoments;

// Window depth d of map c of light k as the distance t in [0, 1] from its near to its far plane.
float shadowLinear(int k, int c, float d) {
    const vec4 m = shadowLights[k].cascades[c].depthMapping;
    return clamp((shadowDistance(k, c, d) - m.z) / (m.w - m.z), 0.0, 1.0);
}

// The exponential warps of EVSM: t' = 2 t - 1 in [-1, 1], exponents clamped for the storage.
vec2 shadowWarp(int k, float t) {
    const vec2 c = clamp(vec2(shadowLights[k].exponent, shadowLights[k].negativeExponent), vec2(0.0), vec2(SHADOW_EVSM_MAX_EXPONENT));
    const float w = 2.0 * t - 1.0;
    return vec2(exp(c.x * w), -exp(-c.y * w));
}

#ifdef MOMENTS_UNORM
// Peters and Klein 2015's basis for 16-bit moments: the four moments of t in [0, 1], so
// transformed (and offset), fill [0, 1] with little quantization error; the blur is linear,
// so it may run on the transformed moments. (The paper's published constants.)
const mat4 shadowMsmEncode = mat4(-2.07224649, 13.7948857237, 0.105877704, 9.7924062118,      //
                                  32.23703778, -59.4683975703, -1.9077466311, -33.7652110555, //
                                  -68.571074599, 82.0359750338, 9.3496555107, 47.9456096605,  //
                                  39.3703274134, -35.364903257, -6.6543490743, -23.9728048165);
const mat4 shadowMsmDecode = mat4(0.2227744146, 0.1549679261, 0.1451988946, 0.163127443,     //
                                  0.0771972861, 0.1394629426, 0.2120202157, 0.2591432266,    //
                                  0.7926986636, 0.7963415838, 0.7258694464, 0.6539092497,    //
                                  0.0319417555, -0.1722823173, -0.2758014811, -0.3376131734);
const float shadowMsmOffset = 0.035955884801;
#endif

// What the moment filters store for distance t (before prefiltering).
vec4 shadowMomentsOf(float t, int k) {
#if FILTER == SHADOW_FILTER_ESM
    return vec4(clamp(shadowLights[k].exponent, 0.0, 80.0) * t, 0.0, 0.0, 0.0); // c t: its log
#elif FILTER == SHADOW_FILTER_EVSM2 || FILTER == SHADOW_FILTER_EVSM4
    const vec2 w = shadowWarp(k, t);
    return vec4(w.x, w.x * w.x, w.y, w.y * w.y);
#elif FILTER == SHADOW_FILTER_MSM && defined(MOMENTS_UNORM)
    return shadowMsmEncode * vec4(t, t * t, t * t * t, t * t * t * t) + vec4(shadowMsmOffset, 0.0, 0.0, 0.0);
#elif FILTER == SHADOW_FILTER_MSM
    return vec4(t, t * t, t * t * t, t * t * t * t);
#else
    return vec4(t, t * t, 0.0, 0.0);
#endif
}

// Chebyshev's one-sided bound that an occluder distribution of mean m.x and second moment
// m.y leaves a receiver at t lit, with the variance floored and light bleeding cut off.
float shadowChebyshev(vec2 m, float t, float minVariance, float bleed) {
    const float variance = max(m.y - m.x * m.x, minVariance);
    const float d = t - m.x;
    const float p = variance / (variance + d * d);
    return t <= m.x ? 1.0 : clamp((p - bleed) / (1.0 - bleed), 0.0, 1.0);
}

// Moment shadow mapping's Hamburger 4MSM (Peters and Klein 2015): the lit fraction at t
// from four moments, biased toward those of a uniform distribution for stability (3e-5 for
// 32F moments).
float shadowHamburger(vec4 b, float t) {
#ifdef MOMENTS_UNORM
    // Back from the 16-bit basis; the paper's bias for 64-bit moments.
    b = mix(shadowMsmDecode * (b - vec4(shadowMsmOffset, 0.0, 0.0, 0.0)), vec4(0.5), 6e-5);
#else
    b = mix(b, vec4(0.5, 0.5, 0.5, 0.5), 3e-5);
#endif
    const float l32d22 = -b.x * b.y + b.z;
    const float d22 = -b.x * b.x + b.y;
    const float squaredVariance = -b.y * b.y + b.w;
    const float d33d22 = dot(vec2(squaredVariance, -l32d22), vec2(d22, l32d22));
    const float invD22 = 1.0 / d22;
    const float l32 = l32d22 * invD22;
    vec3 c = vec3(1.0, t, t * t);
    c.y -= b.x;
    c.z -= b.y + l32 * c.y;
    c.y *= invD22;
    c.z *= d22 / d33d22;
    c.y -= l32 * c.z;
    c.x -= dot(c.yz, b.xy);
    const float p = c.y / c.z, q = c.x / c.z;
    const float r = sqrt(max(p * p * 0.25 - q, 0.0));
    const float z1 = -p * 0.5 - r, z2 = -p * 0.5 + r;
    const vec4 sw = z2 < t ? vec4(z1, t, 1.0, 1.0) : (z1 < t ? vec4(t, z1, 0.0, 1.0) : vec4(0.0));
    const float quotient = (sw.x * z2 - b.x * (sw.x + z2) + b.y) / ((z2 - sw.y) * (t - z1));
    const float shadowed = clamp(sw.z + sw.w * quotient, 0.0, 1.0);
    return allFinite(vec3(shadowed, quotient, 0.0)) ? 1.0 - shadowed : 1.0;
}
#endif

int shadowLightType(int k) { return int(shadowLights[k].lightType); }
bool shadowIsSpot(int k) { return shadowLightType(k) == SHADOW_LIGHT_SPOT; }
// Mapped from a centre, by a cube or paraboloids: point, sphere and rect lights.
bool shadowIsPoint(int k) { return shadowLightType(k) == SHADOW_LIGHT_POINT || shadowLightType(k) == SHADOW_LIGHT_RECT; }
// Lit only within a cone about spot.xyz: spot lights, and rect lights' front half-space.
bool shadowHasCone(int k) { return shadowIsSpot(k) || shadowLightType(k) == SHADOW_LIGHT_RECT; }
bool shadowIsParaboloid(int k, int c) { return shadowLights[k].cascades[c].projection > 1.5; }

// View point p in paraboloid map c's frame (the light at the origin, the map's axis +z).
vec3 shadowInParaboloid(int k, vec3 p, int c) { return (shadowLights[k].cascades[c].viewToLight * vec4(p, 1.0)).xyz; }

// Unit direction from view point p toward the light.
vec3 shadowToLight(int k, vec3 p) {
    const vec3 light = shadowLights[k].light;
    return shadowLightType(k) == SHADOW_LIGHT_DIRECTIONAL ? light : safeNormalize(light - p, -shadowLights[k].spotAxis);
}

// From the light to view point p, in world space (the cube's faces are world-aligned).
vec3 shadowFromLightWorld(int k, vec3 p) { return mat3(frame.viewInverse) * (p - shadowLights[k].light); }

// The cube face whose axis is the major one of world direction d: +x, -x, +y, -y, +z, -z.
int shadowCubeFace(vec3 d) {
    const vec3 a = abs(d);
    return a.x >= a.y && a.x >= a.z ? (d.x >= 0.0 ? 0 : 1) : a.y >= a.z ? (d.y >= 0.0 ? 2 : 3) : (d.z >= 0.0 ? 4 : 5);
}

// World size of one texel of map c at view point p: perspective maps grow with the
// distance along their axis (a cube face's axis is the major one); a paraboloid texel is
// 2 / resolution times |v| + v.z at v in its frame (the projection's derivative).
float shadowTexel(int k, vec3 p, int c) {
    const float t = shadowLights[k].cascades[c].texelSize;
    const vec3 a = abs(shadowFromLightWorld(k, p));
    const vec3 v = shadowInParaboloid(k, p, c);
    const float along = shadowIsSpot(k)                ? max(dot(p - shadowLights[k].light, shadowLights[k].spotAxis), 0.0)
                        : shadowIsParaboloid(k, c) ? length(v) + max(v.z, 0.0)
                                                   : max(a.x, max(a.y, a.z));
    return shadowLightType(k) == SHADOW_LIGHT_DIRECTIONAL ? t : t * along;
}

// Map c's texture coordinate and depth of view point q; w: the clip w (> 0 in front).
// Paraboloid maps: (x, y) = v.xy / (|v| + v.z), depth b / |v| - a, w = |v| + v.z.
vec4 shadowMapCoord(int k, vec3 q, int c) {
    const vec4 clip = shadowLights[k].cascades[c].viewToLight * vec4(q, 1.0);
    const float distance = length(clip.xyz), w = distance + clip.z;
    const vec4 m = shadowLights[k].cascades[c].depthMapping;
    const vec4 paraboloid = vec4(clip.xy / max(w, 1e-30) * 0.5 + 0.5, m.y / max(distance, 1e-30) - m.x, w);
    return shadowIsParaboloid(k, c) ? paraboloid : vec4(clip.xy / clip.w * 0.5 + 0.5, clip.z / clip.w, clip.w);
}

// A point light's map for view point p: the cube face of the major axis of its direction
// from the light, or the paraboloid whose hemisphere holds it (a rect light has one).
int shadowPointMap(int k, vec3 p) {
    const bool second = shadowLights[k].mapCount > 1 && shadowInParaboloid(k, p, 0).z < 0.0;
    return shadowIsParaboloid(k, 0) ? (second ? 1 : 0) : shadowCubeFace(shadowFromLightWorld(k, p));
}

// The slope bias's largest tan(theta).
const float kShadowMaxSlope = 16.0;
// |cos| below which a receiver's plane counts as holding the light (edge-on to its maps):
// 1e-3 rad, far above the rounding of positions reconstructed from depth.
const float kShadowEdgeOnCosine = 1e-3;

// Receiver-plane depth bias (PCF): d depth / d uv of the plane through q with normal n in
// map c, from two points a texel off along the plane; 0 when the light sees the plane
// edge-on, and bounded so that a tap one texel away moves by at most the whole depth range.
// Edge-on means within rounding of it: the light within 1e-3 rad of the plane, or the two
// points' map offsets parallel to 1e-3. A receiver whose plane holds the light (a floor
// through a rect light's centre) would otherwise get a rounding-sized determinant, a gradient
// at the bound, and partial shadow with nothing in the way. Only rounding: a plane a few
// degrees off edge-on (a box's side under a ceiling light) needs its gradient for wide kernels.
vec2 shadowDepthGradient(int k, vec3 q, vec3 n, int c, vec4 centre) {
    const vec3 t1 = safeNormalize(cross(n, abs(n.x) < 0.9 ? vec3(1.0, 0.0, 0.0) : vec3(0.0, 1.0, 0.0)), vec3(0.0));
    const vec3 t2 = cross(n, t1);
    const float e = shadowTexel(k, q, c);
    const vec3 a = shadowMapCoord(k, q + t1 * e, c).xyz - centre.xyz;
    const vec3 b = shadowMapCoord(k, q + t2 * e, c).xyz - centre.xyz;
    const float det = a.x * b.y - a.y * b.x;
    const vec2 g = vec2(a.z * b.y - b.z * a.y, a.x * b.z - b.x * a.z) / det;
    const float limit = float(shadowLights[k].resolution);
    const bool edgeOn = abs(dot(n, shadowToLight(k, q))) < kShadowEdgeOnCosine || !(abs(det) > 1e-3 * length(a.xy) * length(b.xy));
    return !edgeOn && allFinite(vec3(g, 0.0)) ? clamp(g, vec2(-limit), vec2(limit)) : vec2(0.0);
}

// The Poisson disc scaled to `radius` map units, rotated per receiver by interleaved
// gradient noise on its texel position in map c. For a cascade that position is counted from
// where the world origin lands in the map: snapping moves a cascade by whole texels as the
// camera moves, and a static receiver must keep its rotation (else the mask shimmers).
// Spot and point maps do not move with the camera.
mat2 shadowPoissonFrame(int k, int c, vec4 centre, float radius) {
    const bool cascade = shadowLights[k].cascades[c].projection < 0.5;
    const vec2 origin = cascade ? shadowMapCoord(k, frame.view[3].xyz, c).xy : vec2(0.0);
    const vec2 at = (centre.xy - origin) * float(shadowLights[k].resolution);
    const float angle = 6.2831853 * fract(52.9829189 * fract(dot(at, vec2(0.06711056, 0.00583715))));
    return radius * mat2(cos(angle), sin(angle), -sin(angle), cos(angle));
}

// Mean of SHADOW_POISSON_TAPS bilinear comparisons over the disc `spin`, each against the
// receiver's plane at the tap (depth gradient `gradient` per map unit).
float shadowPoissonPcf(int k, vec4 centre, float layer, vec2 gradient, mat2 spin) {
    float lit = 0.0;
    for (int i = 0; i < SHADOW_POISSON_TAPS / 2; ++i) {
        const vec4 pair = shadowLights[k].poisson[i];
        const vec2 a = spin * pair.xy, b = spin * pair.zw;
        lit += texture(shadowMaps, vec4(centre.xy + a, layer, centre.z + dot(gradient, a)));
        lit += texture(shadowMaps, vec4(centre.xy + b, layer, centre.z + dot(gradient, b)));
    }
    return lit / float(SHADOW_POISSON_TAPS);
}

// Pair i of r + 1 along one axis of the optimized grid: its share of the grid's weights
// (1 - f, 1, ..., 1, f) over texels 2i and 2i + 1, and where between them (in texels from
// the first) a bilinear comparison splits that share as the grid does.
vec2 shadowTexelPair(int i, int r, float f) {
    const float first = i == 0 ? 1.0 - f : 1.0, second = i == r ? f : 1.0;
    return vec2(first + second, second / (first + second));
}

// The grid's (2r + 1)^2 comparisons one texel apart, as (r + 1)^2 bilinear comparisons with
// the same weight on every texel (see PcfKernel::OptimizedGrid), each against the
// receiver's plane at its own position.
float shadowOptimizedPcf(int k, vec4 centre, float layer, vec2 gradient, int r) {
    const float size = float(shadowLights[k].resolution);
    const vec2 texels = centre.xy * size - 0.5; // texel centres at whole numbers
    const vec2 below = floor(texels), f = texels - below;
    float lit = 0.0;
    for (int j = 0; j <= r; ++j) {
        const vec2 py = shadowTexelPair(j, r, f.y);
        for (int i = 0; i <= r; ++i) {
            const vec2 px = shadowTexelPair(i, r, f.x);
            const vec2 at = below + vec2(2 * i - r, 2 * j - r) + vec2(px.y, py.y);
            const vec2 offset = (at + 0.5) / size - centre.xy;
            lit += px.x * py.x * texture(shadowMaps, vec4(centre.xy + offset, layer, centre.z + dot(gradient, offset)));
        }
    }
    return lit / float((2 * r + 1) * (2 * r + 1));
}

#if FILTER == SHADOW_FILTER_PCSS
// Percentage-closer soft shadows: the mean depth of the blockers (taps nearer the light than
// the receiver's plane) within the search disc, then a Poisson PCF whose radius is the
// penumbra's half-width R (z_r - z_b) / z_b for a light of radius R, in texels at the
// receiver (one texel spans `receiverTexel` world units there). No blocker: lit.
float shadowPcss(int k, vec3 q, int c, vec4 centre, float layer, vec2 gradient, float receiverTexel) {
    const float texel = 1.0 / float(shadowLights[k].resolution);
    const float lightTexels = shadowLights[k].lightRadius / max(receiverTexel, 1e-30); // R in texels at the receiver
    const float searchTexels = clamp(shadowLights[k].pcssSearchScale * lightTexels, 1.0, float(SHADOW_PCSS_MAX_RADIUS));
    const mat2 search = shadowPoissonFrame(k, c, centre, searchTexels * texel);
    float depthSum = 0.0, blockers = 0.0;
    for (int i = 0; i < SHADOW_POISSON_TAPS / 2; ++i) {
        const vec4 pair = shadowLights[k].poisson[i];
        const vec2 a = search * pair.xy, b = search * pair.zw;
        const float da = texture(shadowDepths, vec3(centre.xy + a, layer)).r;
        const float db = texture(shadowDepths, vec3(centre.xy + b, layer)).r;
        // Reversed-Z: a blocker's depth is greater than the receiver's plane there.
        const bool blockA = da > centre.z + dot(gradient, a), blockB = db > centre.z + dot(gradient, b);
        depthSum += (blockA ? da : 0.0) + (blockB ? db : 0.0);
        blockers += float(blockA) + float(blockB);
    }
    const float zb = shadowDistance(k, c, depthSum / max(blockers, 1.0)), zr = shadowDistance(k, c, centre.z);
    const float halfWidth = shadowLights[k].lightRadius * max(zr - zb, 0.0) / max(zb, 1e-30); // world units
    const float radius = clamp(halfWidth / max(receiverTexel, 1e-30), 0.5, float(SHADOW_PCSS_MAX_RADIUS));
    const float lit = shadowPoissonPcf(k, centre, layer, gradient, shadowPoissonFrame(k, c, centre, radius * texel));
    return blockers > 0.0 ? lit : 1.0;
}
#endif

// Lit fraction at view point q (normal n) in map c: one comparison (Hard, nearest) or a grid
// of bilinear comparisons one texel apart (Pcf; or their optimized or Poisson forms), each against the receiver's plane at the
// tap when receiver-plane bias is on. Points behind the map's eye: unlit.
float shadowLookup(int k, vec3 q, vec3 n, int c) {
    const vec4 centre = shadowMapCoord(k, q, c);
    const float layer = shadowLights[k].cascades[c].layer;
#if SHADOW_FILTER_MOMENTS(FILTER)
    const vec4 m = texture(shadowMoments, vec3(centre.xy, layer));
    const float t = shadowLinear(k, c, centre.z);
    const float minVariance = shadowLights[k].minVariance, bleed = shadowLights[k].lightBleedReduction;
#if FILTER == SHADOW_FILTER_ESM
    const float lit = clamp(exp(m.x - clamp(shadowLights[k].exponent, 0.0, 80.0) * t), 0.0, 1.0);
#elif FILTER == SHADOW_FILTER_EVSM2 || FILTER == SHADOW_FILTER_EVSM4
    // The variance floor in warped units: scaled by the warp's slope at t.
    const vec2 w = shadowWarp(k, t), c2 = 2.0 * clamp(vec2(shadowLights[k].exponent, shadowLights[k].negativeExponent), vec2(0.0), vec2(SHADOW_EVSM_MAX_EXPONENT)) * w;
    // (bounded: c+ = 42 at t = 1 with a floor near 1 would overflow)
    float lit = shadowChebyshev(m.xy, w.x, min(minVariance * c2.x * c2.x, 1e30), bleed);
#if FILTER == SHADOW_FILTER_EVSM4
    lit = min(lit, shadowChebyshev(m.zw, w.y, min(minVariance * c2.y * c2.y, 1e30), bleed));
#endif
#elif FILTER == SHADOW_FILTER_MSM
    const float lit = shadowHamburger(m, t);
#else
    const float lit = shadowChebyshev(m.xy, t, minVariance, bleed);
#endif
    return centre.w > 0.0 ? lit : 0.0;
#else
    const float texel = 1.0 / float(shadowLights[k].resolution);
#if FILTER == SHADOW_FILTER_PCF || FILTER == SHADOW_FILTER_PCSS
    const int r = shadowLights[k].pcfRadius;
    const vec2 gradient = shadowLights[k].receiverPlane != 0 ? shadowDepthGradient(k, q, n, c, centre) : vec2(0.0);
#else
    const int r = 0;
    const vec2 gradient = vec2(0.0);
#endif
    // Single exit: Mesa 22.3 llvmpipe miscompiles early returns inside loops, and the
    // G-buffer calls this inside its loop over lights.
    float lit = 0.0;
#if FILTER == SHADOW_FILTER_PCSS
    lit = shadowPcss(k, q, c, centre, layer, gradient, shadowTexel(k, q, c));
#else
#if FILTER == SHADOW_FILTER_PCF
    const bool poisson = shadowLights[k].pcfKernel == float(SHADOW_PCF_POISSON);
    const bool optimized = shadowLights[k].pcfKernel == float(SHADOW_PCF_OPTIMIZED);
#else
    const bool poisson = false, optimized = false;
#endif
    if (poisson) {
        // The Poisson disc covers the grid's square: radius pcfRadius + 0.5 texels.
        lit = shadowPoissonPcf(k, centre, layer, gradient, shadowPoissonFrame(k, c, centre, (float(r) + 0.5) * texel));
    } else if (optimized) {
        lit = shadowOptimizedPcf(k, centre, layer, gradient, r);
    } else {
        for (int y = -r; y <= r; ++y)
            for (int x = -r; x <= r; ++x) {
                const vec2 offset = vec2(x, y) * texel;
                lit += texture(shadowMaps, vec4(centre.xy + offset, layer, centre.z + dot(gradient, offset)));
            }
        lit /= float((2 * r + 1) * (2 * r + 1));
    }
#endif
    return centre.w > 0.0 ? lit : 0.0;
#endif
}

// The receiver of view point p (geometric normal n, unit direction l to the light, cosine
// c = n.l > 0) for map m: moved toward the light and off the surface by the biases.
vec3 shadowReceiver(int k, vec3 p, vec3 n, vec3 l, float c, int m) {
    const float texel = shadowTexel(k, p, m);
    const float tanTheta = min(sqrt(max(1.0 - c * c, 0.0)) / max(c, 1e-6), kShadowMaxSlope);
    return p + n * (shadowLights[k].normalOffset * texel) +
           l * (shadowLights[k].constantBias + shadowLights[k].slopeBias * texel * tanTheta);
}

// How far the biases move the receiver of view point p (geometric normal n) from it: the
// segment toward the light along which the map cannot see occluders (0 where the light does
// not reach the front side). SSDO's shadow correction marches the screen along it.
float shadowBiasLength(int k, vec3 p, vec3 n) {
    const vec3 l = shadowToLight(k, p);
    const float c = dot(n, l);
    if (!(c > 0.0)) return 0.0;
    int m = 0;
    for (int i = 0; i + 1 < shadowLights[k].mapCount; ++i) m += -p.z > shadowLights[k].cascades[i].sliceEnd ? 1 : 0;
    m = shadowIsPoint(k) ? shadowPointMap(k, p) : m;
    return length(shadowReceiver(k, p, n, l, c, m) - p);
}

// Lit fraction of mapped light k at view point p with geometric normal n: 0 where the light
// does not reach the front side (facing away, outside a spot's cone).
float shadowVisibility(int k, vec3 p, vec3 n) {
    const vec3 l = shadowToLight(k, p);
    const float c = dot(n, l);
    const bool inCone = !shadowHasCone(k) || dot(-l, shadowLights[k].spotAxis) >= shadowLights[k].spotCosOuter;
    // The cascade whose slice holds p's view distance (the last one beyond them all), or
    // the cube face p lies in.
    const float distance = -p.z;
    int m = 0;
    for (int i = 0; i + 1 < shadowLights[k].mapCount; ++i) m += distance > shadowLights[k].cascades[i].sliceEnd ? 1 : 0;
    // A point light's map comes from the biased receiver, which may lie past a face edge or
    // the paraboloids' rim (every cube face has the same texel, so the receiver does not
    // depend on the face; a paraboloid's does a little: the map p lies in sets it).
    m = shadowIsPoint(k) && c > 0.0 ? shadowPointMap(k, shadowReceiver(k, p, n, l, c, shadowPointMap(k, p))) : m;
    // A rect light may light a receiver that faces away from its centre (part of it is above
    // the receiver's horizon); the map from the centre cannot tell, so such receivers count
    // as lit (what the light's own shading then clips). So do receivers whose plane holds
    // the centre to within 1e-3 rad (rounding of reconstructed positions): the sign of their
    // cosine is noise, and their biased receiver lies off the plane the map leaves out.
    const bool facesAway = shadowLightType(k) == SHADOW_LIGHT_RECT ? !(c > kShadowEdgeOnCosine) : !(c > 0.0);
    float v = shadowLightType(k) == SHADOW_LIGHT_RECT && inCone && facesAway ? 1.0 : 0.0;
    if (!facesAway && inCone) {
        v = shadowLookup(k, shadowReceiver(k, p, n, l, c, m), n, m);
        // Blend into the next cascade over the end of this slice (cascades only).
        const float end = shadowLights[k].cascades[m].sliceEnd;
        const float start = m > 0 ? shadowLights[k].cascades[max(m - 1, 0)].sliceEnd : shadowLights[k].firstSliceStart;
        const float band = shadowLights[k].cascadeBlend * (end - start);
        const float t = band > 0.0 ? clamp((distance - (end - band)) / band, 0.0, 1.0) : 0.0;
        if (!shadowIsPoint(k) && m + 1 < shadowLights[k].mapCount && t > 0.0)
            v = mix(v, shadowLookup(k, shadowReceiver(k, p, n, l, c, m + 1), n, m + 1), t);
    }
    return v;
}

