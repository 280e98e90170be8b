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

bool shadowIsSpot() { return int(shadow.light.w) == SHADOW_LIGHT_SPOT; }

// Unit direction from view point p toward the light.
vec3 shadowToLight(vec3 p) {
    return shadowIsSpot() ? safeNormalize(shadow.light.xyz - p, -shadow.spot.xyz) : shadow.light.xyz;
}

// World size of one texel of map c at view point p.
float shadowTexel(vec3 p, int c) {
    const float t = shadow.cascades[c].info.y;
    return shadowIsSpot() ? t * max(dot(p - shadow.light.xyz, shadow.spot.xyz), 0.0) : t;
}

// Lit fraction at view point q in map c: one comparison (Hard, nearest) or a grid of
// bilinear comparisons one texel apart (Pcf). Points in front of the map's eye: unlit.
float shadowLookup(vec3 q, int c) {
    const vec4 clip = shadow.cascades[c].viewToLight * vec4(q, 1.0);
    const vec3 ndc = clip.xyz / clip.w;
    const vec2 uv = ndc.xy * 0.5 + 0.5;
    const float layer = shadow.cascades[c].info.z;
#if FILTER == SHADOW_FILTER_PCF
    const int r = shadow.counts.z;
#else
    const int r = 0;
#endif
    const float texel = 1.0 / float(shadow.counts.w);
    float lit = 0.0;
    for (int y = -r; y <= r; ++y)
        for (int x = -r; x <= r; ++x) lit += texture(shadowMaps, vec4(uv + vec2(x, y) * texel, layer, ndc.z));
    const float n = float((2 * r + 1) * (2 * r + 1));
    return clip.w > 0.0 ? lit / n : 0.0;
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
    // The cascade whose slice holds p's view distance (the last one beyond them all).
    const float distance = -p.z;
    int m = 0;
    for (int i = 0; i + 1 < shadow.counts.x; ++i) m += distance > shadow.cascades[i].info.x ? 1 : 0;
    float v = 0.0;
    if (c > 0.0 && inCone) {
        v = shadowLookup(shadowReceiver(p, n, l, c, m), m);
        // Blend into the next cascade over the end of this slice.
        const float end = shadow.cascades[m].info.x;
        const float start = m > 0 ? shadow.cascades[max(m - 1, 0)].info.x : 0.0;
        const float band = shadow.bias.w * (end - start);
        const float t = band > 0.0 ? clamp((distance - (end - band)) / band, 0.0, 1.0) : 0.0;
        if (m + 1 < shadow.counts.x && t > 0.0) v = mix(v, shadowLookup(shadowReceiver(p, n, l, c, m + 1), m + 1), t);
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
