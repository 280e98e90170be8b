// Shadow-map lookups for a mapped light (see obscura/shadow_maps.hpp): which map a receiver
// uses, the biased receiver, and the lit fraction of the filter's comparisons. Reads the
// ShadowParams records at SHADOW_LIGHTS_SSBO and the maps at SHADOW_MAP_UNIT; needs
// frame.glsl's block (view space is the frame's). FILTER: SHADOW_FILTER_HARD (default) or
// SHADOW_FILTER_PCF, matching the sampler bound with the maps (nearest or linear).
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

int shadowLightType(int k) { return int(shadowLights[k].light.w); }
bool shadowIsSpot(int k) { return shadowLightType(k) == SHADOW_LIGHT_SPOT; }
bool shadowIsPoint(int k) { return shadowLightType(k) == SHADOW_LIGHT_POINT; }

// Unit direction from view point p toward the light.
vec3 shadowToLight(int k, vec3 p) {
    const vec4 light = shadowLights[k].light;
    return int(light.w) == SHADOW_LIGHT_DIRECTIONAL ? light.xyz : safeNormalize(light.xyz - p, -shadowLights[k].spot.xyz);
}

// From the light to view point p, in world space (the cube's faces are world-aligned).
vec3 shadowFromLightWorld(int k, vec3 p) { return mat3(frame.viewInverse) * (p - shadowLights[k].light.xyz); }

// The cube face whose axis is the major one of world direction d: +x, -x, +y, -y, +z, -z.
int shadowCubeFace(vec3 d) {
    const vec3 a = abs(d);
    return a.x >= a.y && a.x >= a.z ? (d.x >= 0.0 ? 0 : 1) : a.y >= a.z ? (d.y >= 0.0 ? 2 : 3) : (d.z >= 0.0 ? 4 : 5);
}

// World size of one texel of map c at view point p: perspective maps grow with the
// distance along their axis (a cube face's axis is the major one).
float shadowTexel(int k, vec3 p, int c) {
    const float t = shadowLights[k].cascades[c].info.y;
    const vec3 a = abs(shadowFromLightWorld(k, p));
    const float along = shadowIsSpot(k) ? max(dot(p - shadowLights[k].light.xyz, shadowLights[k].spot.xyz), 0.0)
                                        : max(a.x, max(a.y, a.z));
    return shadowLightType(k) == SHADOW_LIGHT_DIRECTIONAL ? t : t * along;
}

// Map c's texture coordinate and depth of view point q; w: the clip w (> 0 in front).
vec4 shadowMapCoord(int k, vec3 q, int c) {
    const vec4 clip = shadowLights[k].cascades[c].viewToLight * vec4(q, 1.0);
    return vec4(clip.xy / clip.w * 0.5 + 0.5, clip.z / clip.w, clip.w);
}

// Receiver-plane depth bias (PCF): d depth / d uv of the plane through q with normal n in
// map c, from two points a texel off along the plane; 0 when the light sees the plane
// edge-on, and bounded so that a tap one texel away moves by at most the whole depth range.
vec2 shadowDepthGradient(int k, vec3 q, vec3 n, int c, vec4 centre) {
    const vec3 t1 = safeNormalize(cross(n, abs(n.x) < 0.9 ? vec3(1.0, 0.0, 0.0) : vec3(0.0, 1.0, 0.0)), vec3(0.0));
    const vec3 t2 = cross(n, t1);
    const float e = shadowTexel(k, q, c);
    const vec3 a = shadowMapCoord(k, q + t1 * e, c).xyz - centre.xyz;
    const vec3 b = shadowMapCoord(k, q + t2 * e, c).xyz - centre.xyz;
    const float det = a.x * b.y - a.y * b.x;
    const vec2 g = vec2(a.z * b.y - b.z * a.y, a.x * b.z - b.x * a.z) / det;
    const float limit = float(shadowLights[k].counts.w);
    return abs(det) > 0.0 && allFinite(vec3(g, 0.0)) ? clamp(g, vec2(-limit), vec2(limit)) : vec2(0.0);
}

// Lit fraction at view point q (normal n) in map c: one comparison (Hard, nearest) or a grid
// of bilinear comparisons one texel apart (Pcf), each against the receiver's plane at the
// tap when receiver-plane bias is on. Points behind the map's eye: unlit.
float shadowLookup(int k, vec3 q, vec3 n, int c) {
    const vec4 centre = shadowMapCoord(k, q, c);
    const float layer = shadowLights[k].cascades[c].info.z;
    const float texel = 1.0 / float(shadowLights[k].counts.w);
#if FILTER == SHADOW_FILTER_PCF
    const int r = shadowLights[k].counts.z;
    const vec2 gradient = shadowLights[k].counts.y != 0 ? shadowDepthGradient(k, q, n, c, centre) : vec2(0.0);
#else
    const int r = 0;
    const vec2 gradient = vec2(0.0);
#endif
    float lit = 0.0;
    for (int y = -r; y <= r; ++y)
        for (int x = -r; x <= r; ++x) {
            const vec2 offset = vec2(x, y) * texel;
            lit += texture(shadowMaps, vec4(centre.xy + offset, layer, centre.z + dot(gradient, offset)));
        }
    const float count = float((2 * r + 1) * (2 * r + 1));
    return centre.w > 0.0 ? lit / count : 0.0;
}

// The receiver of view point p (geometric normal n, unit direction l to the light, cosine
// c = n.l > 0) for map m: moved toward the light and off the surface by the biases.
vec3 shadowReceiver(int k, vec3 p, vec3 n, vec3 l, float c, int m) {
    const float texel = shadowTexel(k, p, m);
    const float tanTheta = min(sqrt(max(1.0 - c * c, 0.0)) / max(c, 1e-6), 16.0);
    const vec4 bias = shadowLights[k].bias;
    return p + n * (bias.z * texel) + l * (bias.x + bias.y * texel * tanTheta);
}

// Lit fraction of mapped light k at view point p with geometric normal n: 0 where the light
// does not reach the front side (facing away, outside a spot's cone).
float shadowVisibility(int k, vec3 p, vec3 n) {
    const vec3 l = shadowToLight(k, p);
    const float c = dot(n, l);
    const bool inCone = !shadowIsSpot(k) || dot(-l, shadowLights[k].spot.xyz) >= shadowLights[k].spot.w;
    // The cascade whose slice holds p's view distance (the last one beyond them all), or
    // the cube face p lies in.
    const float distance = -p.z;
    int m = 0;
    for (int i = 0; i + 1 < shadowLights[k].counts.x; ++i) m += distance > shadowLights[k].cascades[i].info.x ? 1 : 0;
    m = shadowIsPoint(k) ? shadowCubeFace(shadowFromLightWorld(k, p)) : m;
    float v = 0.0;
    if (c > 0.0 && inCone) {
        v = shadowLookup(k, shadowReceiver(k, p, n, l, c, m), n, m);
        // Blend into the next cascade over the end of this slice (cascades only).
        const float end = shadowLights[k].cascades[m].info.x;
        const float start = m > 0 ? shadowLights[k].cascades[max(m - 1, 0)].info.x : 0.0;
        const float band = shadowLights[k].bias.w * (end - start);
        const float t = band > 0.0 ? clamp((distance - (end - band)) / band, 0.0, 1.0) : 0.0;
        if (!shadowIsPoint(k) && m + 1 < shadowLights[k].counts.x && t > 0.0)
            v = mix(v, shadowLookup(k, shadowReceiver(k, p, n, l, c, m + 1), n, m + 1), t);
    }
    return v;
}

