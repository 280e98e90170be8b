//! variant: HAS_NORMALS
//! variant: HAS_NORMALS HAS_TEXCOORDS ALBEDO_TEXTURE
//! variant: NO_DIRECT_LIGHTING
//! variant: PEEL
//! variant: HAS_NORMALS PEEL
#ifdef PEEL
#define NO_DIRECT_LIGHTING // depth only
#endif
#include "../common/frame.glsl"
#include "../common/math.glsl"
#include "gbuffer_bindings.h"

in FragmentData {
    vec3 viewPosition;
    vec3 shadingNormal;
    vec2 texcoord;
    flat vec3 faceNormal;
} fin;

layout(location = 0) out vec4 outNormal;
layout(location = 1) out vec4 outAlbedo;
layout(location = 2) out vec4 outDirect;

layout(location = GBUFFER_LOC_ALBEDO) uniform vec3 materialAlbedo;
layout(location = GBUFFER_LOC_EMISSION) uniform vec3 materialEmission;
layout(location = GBUFFER_LOC_LIGHT_COUNT) uniform int lightCount;

#ifdef ALBEDO_TEXTURE
layout(binding = GBUFFER_ALBEDO_TEXTURE_UNIT) uniform sampler2D albedoTexture;
#endif

#ifdef PEEL
// The first depth layer: the peeling pass keeps only what lies strictly behind it.
layout(binding = GBUFFER_DEPTH_TEXTURE_UNIT) uniform sampler2D firstLayer;
#endif

layout(std430, binding = GBUFFER_LIGHTS_SSBO_BINDING) readonly buffer Lights {
    LightData lights[];
};

// Smooth cone from cos(outer) to cos(inner); a hard edge when they coincide (smoothstep
// is undefined for equal edges).
float spotCone(float c, float cosInner, float cosOuter) {
    float width = cosInner - cosOuter;
    if (!(width > 0.0)) return c >= cosOuter ? 1.0 : 0.0;
    float t = clamp((c - cosOuter) / width, 0.0, 1.0);
    return t * t * (3.0 - 2.0 * t);
}

// Projected solid angle of a one-sided rectangle seen from p (normal n): Lambert's formula
// for polygons, after clipping the rectangle to the hemisphere above p. Exact; per unit
// radiance it is the irradiance.
float rectProjectedSolidAngle(vec3 p, vec3 n, LightData light) {
    vec3 centre = light.positionType.xyz - p;
    if (dot(-centre, light.directionRadius.xyz) <= 0.0) return 0.0; // p is behind the emitting side
    vec3 u = light.extent.xyz;
    vec3 v = normalize(cross(light.directionRadius.xyz, u)) * light.extent.w;
    vec3 corners[4] = vec3[4](centre - u - v, centre + u - v, centre + u + v, centre - u + v);
    // Sutherland-Hodgman against the plane dot(x, n) = 0: at most 5 vertices remain.
    vec3 poly[5];
    int count = 0;
    for (int i = 0; i < 4; ++i) {
        vec3 a = corners[i], b = corners[(i + 1) % 4];
        float da = dot(a, n), db = dot(b, n);
        if (da >= 0.0) poly[count++] = a;
        if ((da >= 0.0) != (db >= 0.0)) poly[count++] = a + (b - a) * (da / (da - db));
    }
    float sum = 0.0;
    for (int i = 0; i < count; ++i) {
        vec3 a = safeNormalize(poly[i], vec3(0.0)), b = safeNormalize(poly[(i + 1) % count], vec3(0.0));
        vec3 c = cross(a, b);
        float s = length(c);
        // atan(|a x b|, a.b) keeps the edge angle accurate for tiny, distant rectangles.
        if (s > 0.0) sum += atan(s, dot(a, b)) * dot(c / s, n);
    }
    return 0.5 * abs(sum);
}

// Irradiance from one light at view-space point p with shading normal ns; lights behind
// the geometric surface (ng) contribute nothing.
vec3 irradiance(LightData light, vec3 p, vec3 ns, vec3 ng) {
    int type = int(light.positionType.w);
    if (type == GBUFFER_LIGHT_RECT) return light.radiance.rgb * rectProjectedSolidAngle(p, ns, light);
    vec3 l;
    float falloff = 1.0;
    if (type == GBUFFER_LIGHT_DIRECTIONAL) {
        l = -light.directionRadius.xyz;
    } else {
        vec3 toLight = light.positionType.xyz - p;
        float d2 = dot(toLight, toLight);
        if (!(d2 > 0.0)) return vec3(0.0); // at the light itself the direction is undefined
        l = toLight * inversesqrt(d2);
        float r = light.directionRadius.w;
        // Bounded by the largest float so that falloff * cos is never Inf * 0 = NaN.
        falloff = min(1.0 / max(d2, r * r), kFloatMax);
        if (type == GBUFFER_LIGHT_SPOT) falloff *= spotCone(dot(-l, light.directionRadius.xyz), light.cone.x, light.cone.y);
        // A Lambertian sphere of radiance L has intensity pi r^2 L in every direction: exact
        // while it is entirely above the horizon, an approximation (cosine at its centre) near it.
        if (type == GBUFFER_LIGHT_SPHERE) falloff *= OBSCURA_PI * r * r;
    }
    if (dot(ng, l) <= 0.0) return vec3(0.0);
    return light.radiance.rgb * (falloff * max(dot(ns, l), 0.0));
}

void main() {
#ifdef PEEL
    // Same vertices, same invariant positions: the first layer's own fragments reproduce its
    // depth exactly and are dropped; viewport.w = 1 marks reversed-Z (farther = smaller).
    const float front = texelFetch(firstLayer, ivec2(gl_FragCoord.xy), 0).r;
    const bool behind = frame.viewport.w == 1 ? gl_FragCoord.z < front : gl_FragCoord.z > front;
    if (!behind) discard;
#endif
    vec3 ng = fin.faceNormal;
    vec3 ns = ng;
#ifdef HAS_NORMALS
    ns = safeNormalize(fin.shadingNormal, ng);
    if (dot(ns, ng) < 0.0) ns = -ns; // two-sided: shade the side the camera sees
#endif
    vec3 albedo = materialAlbedo;
#ifdef ALBEDO_TEXTURE
    albedo *= texture(albedoTexture, fin.texcoord).rgb;
#endif
    albedo = clamp(albedo, vec3(0.0), vec3(1.0));

    vec3 radiance = materialEmission;
#ifndef NO_DIRECT_LIGHTING
    vec3 e = vec3(0.0);
    for (int i = 0; i < lightCount; ++i) e += irradiance(lights[i], fin.viewPosition, ns, ng);
    radiance += albedo * (1.0 / OBSCURA_PI) * e;
#endif
    outNormal = vec4(ng, 1.0);
    outAlbedo = vec4(albedo, 1.0);
    outDirect = vec4(clampRadiance(radiance), 1.0);
}
