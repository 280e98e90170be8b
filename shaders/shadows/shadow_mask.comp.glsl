// The shadow mask of one light at the G-buffer's samples: per pixel the fraction of the
// filter's depth comparisons that find the biased receiver lit (see shadow_maps.hpp).
//! variant: FILTER=0
//! variant: FILTER=1
#include "../visibility/screen_march.glsl"
#include "shadow_bindings.h"

#ifndef FILTER
#define FILTER SHADOW_FILTER_HARD
#endif

layout(local_size_x = SHADOW_WORKGROUP, local_size_y = SHADOW_WORKGROUP) in;
layout(std140, binding = SHADOW_PARAMS_UBO_BINDING) uniform ShadowBlock {
    ShadowParams shadow;
};
layout(binding = SHADOW_MAP_UNIT) uniform sampler2DArrayShadow shadowMaps;
layout(binding = SHADOW_MASK_IMAGE, r16f) writeonly uniform image2D maskOut;

int shadowLightType() { return int(shadow.light.w); }
bool shadowIsSpot() { return shadowLightType() == SHADOW_LIGHT_SPOT; }
bool shadowIsPoint() { return shadowLightType() == SHADOW_LIGHT_POINT; }

// Unit direction from view point p toward the light.
vec3 shadowToLight(vec3 p) {
    return shadowLightType() == SHADOW_LIGHT_DIRECTIONAL ? shadow.light.xyz
                                                         : safeNormalize(shadow.light.xyz - p, -shadow.spot.xyz);
}

// From the light to view point p, in world space (the cube's faces are world-aligned).
vec3 shadowFromLightWorld(vec3 p) { return mat3(frame.viewInverse) * (p - shadow.light.xyz); }

// The cube face whose axis is the major one of world direction d: +x, -x, +y, -y, +z, -z.
int shadowCubeFace(vec3 d) {
    const vec3 a = abs(d);
    return a.x >= a.y && a.x >= a.z ? (d.x >= 0.0 ? 0 : 1) : a.y >= a.z ? (d.y >= 0.0 ? 2 : 3) : (d.z >= 0.0 ? 4 : 5);
}

// World size of one texel of map c at view point p: perspective maps grow with the
// distance along their axis (a cube face's axis is the major one).
float shadowTexel(vec3 p, int c) {
    const float t = shadow.cascades[c].info.y;
    const vec3 a = abs(shadowFromLightWorld(p));
    const float along = shadowIsSpot() ? max(dot(p - shadow.light.xyz, shadow.spot.xyz), 0.0) : max(a.x, max(a.y, a.z));
    return shadowLightType() == SHADOW_LIGHT_DIRECTIONAL ? t : t * along;
}

// Map c's texture coordinate and depth of view point q; w: the clip w (> 0 in front).
vec4 shadowMapCoord(vec3 q, int c) {
    const vec4 clip = shadow.cascades[c].viewToLight * vec4(q, 1.0);
    return vec4(clip.xy / clip.w * 0.5 + 0.5, clip.z / clip.w, clip.w);
}

// Receiver-plane depth bias (PCF): d depth / d uv of the plane through q with normal n in
// map c, from two points a texel off along the plane; 0 when the light sees the plane
// edge-on, and bounded so that a tap one texel away moves by at most the whole depth range.
vec2 shadowDepthGradient(vec3 q, vec3 n, int c, vec4 centre) {
    const vec3 t1 = safeNormalize(cross(n, abs(n.x) < 0.9 ? vec3(1.0, 0.0, 0.0) : vec3(0.0, 1.0, 0.0)), vec3(0.0));
    const vec3 t2 = cross(n, t1);
    const float e = shadowTexel(q, c);
    const vec3 a = shadowMapCoord(q + t1 * e, c).xyz - centre.xyz, b = shadowMapCoord(q + t2 * e, c).xyz - centre.xyz;
    const float det = a.x * b.y - a.y * b.x;
    const vec2 g = vec2(a.z * b.y - b.z * a.y, a.x * b.z - b.x * a.z) / det;
    const float limit = float(shadow.counts.w);
    return abs(det) > 0.0 && allFinite(vec3(g, 0.0)) ? clamp(g, vec2(-limit), vec2(limit)) : vec2(0.0);
}

// Lit fraction at view point q (normal n) in map c: one comparison (Hard, nearest) or a grid
// of bilinear comparisons one texel apart (Pcf), each against the receiver's plane at the
// tap when receiver-plane bias is on. Points behind the map's eye: unlit.
float shadowLookup(vec3 q, vec3 n, int c) {
    const vec4 centre = shadowMapCoord(q, c);
    const float layer = shadow.cascades[c].info.z;
    const float texel = 1.0 / float(shadow.counts.w);
#if FILTER == SHADOW_FILTER_PCF
    const int r = shadow.counts.z;
    const vec2 gradient = shadow.counts.y != 0 ? shadowDepthGradient(q, n, c, centre) : vec2(0.0);
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
vec3 shadowReceiver(vec3 p, vec3 n, vec3 l, float c, int m) {
    const float texel = shadowTexel(p, m);
    const float tanTheta = min(sqrt(max(1.0 - c * c, 0.0)) / max(c, 1e-6), 16.0);
    return p + n * (shadow.bias.z * texel) + l * (shadow.bias.x + shadow.bias.y * texel * tanTheta);
}

float shadowVisibility(vec3 p, vec3 n) {
    const vec3 l = shadowToLight(p);
    const float c = dot(n, l);
    const bool inCone = !shadowIsSpot() || dot(-l, shadow.spot.xyz) >= shadow.spot.w;
    // The cascade whose slice holds p's view distance (the last one beyond them all), or
    // the cube face p lies in.
    const float distance = -p.z;
    int m = 0;
    for (int i = 0; i + 1 < shadow.counts.x; ++i) m += distance > shadow.cascades[i].info.x ? 1 : 0;
    m = shadowIsPoint() ? shadowCubeFace(shadowFromLightWorld(p)) : m;
    float v = 0.0;
    if (c > 0.0 && inCone) {
        v = shadowLookup(shadowReceiver(p, n, l, c, m), n, m);
        // Blend into the next cascade over the end of this slice (cascades only).
        const float end = shadow.cascades[m].info.x;
        const float start = m > 0 ? shadow.cascades[max(m - 1, 0)].info.x : 0.0;
        const float band = shadow.bias.w * (end - start);
        const float t = band > 0.0 ? clamp((distance - (end - band)) / band, 0.0, 1.0) : 0.0;
        if (!shadowIsPoint() && m + 1 < shadow.counts.x && t > 0.0) v = mix(v, shadowLookup(shadowReceiver(p, n, l, c, m + 1), n, m + 1), t);
    }
    return v;
}

void main() {
    const ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(pixel, frameSize()))) return;
    const float depth = texelFetch(visDepth, pixel, 0).r;
    const vec4 normalTexel = texelFetch(visNormal, pixel, 0);
    float v = 1.0;
    if (!isBackground(depth) && normalTexel.a != 0.0) {
        const vec3 p = viewPositionFromDepth(pixelCenterUv(pixel), depth);
        v = shadowVisibility(p, safeNormalize(normalTexel.xyz, viewDirectionTo(p)));
    }
    imageStore(maskOut, pixel, vec4(clamp(v, 0.0, 1.0)));
}
