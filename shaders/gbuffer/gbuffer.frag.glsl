//! variant: HAS_NORMALS
//! variant: HAS_NORMALS RECT_LIGHTS
//! variant: HAS_NORMALS SHADOWS FILTER=0
//! variant: HAS_NORMALS RECT_LIGHTS SHADOWS FILTER=1
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
#ifdef SHADOWS
#include "../shadows/shadow_sample.glsl"
#endif

in FragmentData {
    vec3 viewPosition;
    vec3 shadingNormal;
    vec2 texcoord;
    flat vec3 faceNormal;
    flat float frontSide;
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

#include "light_irradiance.glsl"

void main() {
#ifdef PEEL
    // Same vertices, same invariant positions: the first layer's own fragments reproduce its
    // depth exactly and are dropped; frame.reversedZ = 1 marks reversed-Z (farther = smaller).
    const float front = texelFetch(firstLayer, ivec2(gl_FragCoord.xy), 0).r;
    const bool behind = frame.reversedZ == 1 ? gl_FragCoord.z < front : gl_FragCoord.z > front;
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

    vec3 radiance = materialEmission * fin.frontSide; // materials emit from their front side
#ifndef NO_DIRECT_LIGHTING
    vec3 e = vec3(0.0);
    for (int i = 0; i < lightCount; ++i) {
        float visible = 1.0;
#ifdef SHADOWS
        // cone.z: the light's shadow record, or -1 (see GBufferSettings::shadows).
        const int record = int(lights[i].shadowRecord);
        if (record >= 0) visible = shadowVisibility(record, fin.viewPosition, ng);
#endif
        e += irradiance(lights[i], fin.viewPosition, ns, ng) * visible;
    }
    radiance += albedo * (1.0 / OBSCURA_PI) * e;
#endif
    outNormal = vec4(ng, 1.0);
    outAlbedo = vec4(albedo, 1.0);
    outDirect = vec4(clampRadiance(radiance), 1.0);
}
