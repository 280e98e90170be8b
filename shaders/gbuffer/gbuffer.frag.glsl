//! variant: HAS_NORMALS
//! variant: HAS_NORMALS HAS_TEXCOORDS ALBEDO_TEXTURE
//! variant: NO_DIRECT_LIGHTING
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

// Irradiance from one light at view-space point p with shading normal ns; lights behind
// the geometric surface (ng) contribute nothing.
vec3 irradiance(LightData light, vec3 p, vec3 ns, vec3 ng) {
    int type = int(light.positionType.w);
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
    }
    if (dot(ng, l) <= 0.0) return vec3(0.0);
    return light.radiance.rgb * (falloff * max(dot(ns, l), 0.0));
}

void main() {
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
