// SSDO's lights pass, at the G-buffer's resolution: `direct` = the environment term (the
// direct pass's result, albedo included) + (albedo / pi) Sum_lights E_l V_l, E_l the light's
// irradiance (light_irradiance.glsl, the G-buffer's), V_l its shadow maps' lit fraction
// (SHADOWS) times the shadow correction (CORRECTION): the biases move a map's receiver toward
// the light, so occluders on that segment (contact shadows) are missed; a screen-space march
// from the pixel toward the light over shadowCorrection times that segment puts them back
// (ShadowMaskSettings' contactSteps samples, thin as its contactThickness, so that rays
// passing behind an occluder stay lit).
//! Every permutation the module compiles (validated by glslangValidator at build time):
//! variant:
//! variant: RECT_LIGHTS
//! variant: SHADOWS FILTER=0
//! variant: SHADOWS FILTER=1 CORRECTION
//! variant: RECT_LIGHTS SHADOWS FILTER=1 CORRECTION
//! variant: SHADOWS FILTER=0 CORRECTION SCREEN_MARCH=1 SCREEN_PEELED
#include "../common/sampling.glsl"
#include "../visibility/screen_march.glsl"
#include "../gbuffer/gbuffer_bindings.h"
#include "../gbuffer/light_irradiance.glsl"
#ifdef SHADOWS
#include "../shadows/shadow_sample.glsl"
#endif
#include "ssdo_bindings.h"

layout(local_size_x = SSDO_WORKGROUP, local_size_y = SSDO_WORKGROUP, local_size_z = 1) in;
layout(std140, binding = SSDO_PARAMS_UBO_BINDING) uniform SsdoBlock {
    SsdoParams ssdo;
};
layout(binding = SSDO_ENVIRONMENT_TERM_UNIT) uniform sampler2D environmentTerm;
layout(binding = SSDO_ALBEDO_UNIT) uniform sampler2D albedoTexture;
layout(binding = SSDO_OUT_IMAGE, rgba16f) writeonly uniform image2D directOut;

// The unit direction from p to light i (its centre), and the distance (infinite for a
// directional light).
vec3 ssdoToLight(LightData light, vec3 p, out float distance) {
    if (int(light.type) == GBUFFER_LIGHT_DIRECTIONAL) {
        distance = kFloatMax;
        return -light.direction;
    }
    const vec3 d = light.position - p;
    distance = length(d);
    return safeNormalize(d, vec3(0.0, 0.0, 1.0));
}

#if defined(SHADOWS) && defined(CORRECTION)
// 0 where the screen shows an occluder on the segment toward the light the map's biases hide.
float ssdoCorrection(int record, LightData light, vec3 p, vec3 n, float normalError, ivec2 pixel) {
    float distance;
    const vec3 l = ssdoToLight(light, p, distance);
    const float reach = min(ssdo.shadowCorrection * shadowBiasLength(record, p, n), distance);
    if (!(reach > 0.0)) return 1.0;
    const float hit = screenMarch(ScreenRayStart(p, n, normalError), l, reach, ssdo.contactSteps,
                                  pixelJitter(pixel, frame.sampleShift), ssdo.contactThickness);
    return hit < 0.0 ? 1.0 : 0.0;
}
#endif

void main() {
    const ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(pixel, frameSize()))) return;
    const vec4 env = texelFetch(environmentTerm, pixel, 0);
    const float depth = texelFetch(visDepth, pixel, 0).r;
    const vec4 normalTexel = texelFetch(visNormal, pixel, 0);
    if (isBackground(depth) || normalTexel.a == 0.0) {
        imageStore(directOut, pixel, vec4(0.0));
        return;
    }
    const vec3 p = viewPositionFromDepth(pixelCenterUv(pixel), depth);
    const vec3 n = safeNormalize(normalTexel.xyz, viewDirectionTo(p));
    vec3 e = vec3(0.0);
    for (int i = 0; i < ssdo.lightCount; ++i) {
        float visible = 1.0;
#ifdef SHADOWS
        const int record = int(lights[i].shadowRecord);
        if (record >= 0) {
            visible = shadowVisibility(record, p, n);
#ifdef CORRECTION
            if (visible > 0.0) visible *= ssdoCorrection(record, lights[i], p, n, storedNormalError(normalTexel), pixel);
#endif
        }
#endif
        e += irradiance(lights[i], p, n, n) * visible;
    }
    const vec3 albedo = clampAlbedo(texelFetch(albedoTexture, pixel, 0).rgb);
    imageStore(directOut, pixel, roundedToHalf(vec4(clampRadiance(env.rgb + albedo * (1.0 / OBSCURA_PI) * e), 1.0)));
}
