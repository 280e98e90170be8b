// media.raymarch: single scattering along each pixel's view ray by marching `steps` samples
// over the part of it inside the media (first entry to last exit, up to the surface), each
// step jittered per pixel and integrated with the energy-conserving step (Hillaire 2015):
//   L += T(0, t) Sum_lights sigma_s p L_i T(t, light) V(t) * dt (1 - exp(-sigma_t dt)) / (sigma_t dt)
// so that a dense medium tends to sigma_s/sigma_t times the source, never beyond it. T toward
// the lights is exact per box; V comes from the shadow maps (SHADOWS). The optical depth
// stored is the view ray's exact one (the boxes' lengths times sigma_t), whatever the steps.
//! Every permutation the module compiles (validated by glslangValidator at build time):
//! variant:
//! variant: SHADOWS
#include "../common/depth.glsl"
#include "../common/sampling.glsl"
#include "../gbuffer/gbuffer_bindings.h"
#include "../gbuffer/light_irradiance.glsl"
#ifdef SHADOWS
#include "../shadows/shadow_sample.glsl"
#endif
#include "media_common.glsl"
#include "media_shadow.glsl"

layout(local_size_x = MEDIA_WORKGROUP, local_size_y = MEDIA_WORKGROUP, local_size_z = 1) in;
layout(binding = MEDIA_DEPTH_UNIT) uniform sampler2D depthTexture;
layout(binding = MEDIA_OUT_IMAGE, rgba16f) writeonly uniform image2D scatteringOut;
layout(binding = MEDIA_DEPTH_OUT_IMAGE, rgba16f) writeonly uniform image2D depthOut;

// The light scattered toward the camera at view point x (world xw) per unit length, before
// the view side's transmittance: Sum_lights sigma_s p L_i T(x, light) V.
vec3 mediaInScattering(vec3 x, vec3 xw, vec3 viewDirection) {
    vec3 sum = vec3(0.0);
    for (int i = 0; i < media.lightCount; ++i) {
        vec3 toLight;
        float distance;
        const vec3 e = mediaLightAt(i, x, toLight, distance);
        const float visible = mediaLightVisibility(i, x, toLight);
        const vec3 tau = mediaOpticalDepth(xw, mediaDirectionToWorld(toLight), distance);
        // The angle between the light's travel direction (-toLight) and the way to the camera.
        sum += mediaScatteringPhase(xw, dot(toLight, viewDirection)) * e * (visible * exp(-tau));
    }
    return sum;
}

void main() {
    const ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(pixel, media.size))) return;
    const MediaRay r = mediaViewRay(pixel, texelFetch(depthTexture, pixel, 0).r);
    const vec3 ow = mediaToWorld(r.origin), ww = mediaDirectionToWorld(r.direction);
    const vec2 span = mediaSpan(ow, ww, r.end);
    vec3 radiance = vec3(0.0);
    if (span.y > span.x) {
        const float dt = (span.y - span.x) / float(media.steps);
        const float jitter = media.jitter != 0 ? pixelJitter(pixel, frame.sampleShift) : 0.5;
        vec3 tau = vec3(0.0); // from the camera to the current step's start
        for (int s = 0; s < media.steps; ++s) {
            const float t = span.x + (float(s) + jitter) * dt;
            const vec3 xw = ow + t * ww;
            vec3 scattering, extinction;
            mediaCoefficientsAt(xw, scattering, extinction);
            const vec3 stepTau = extinction * dt;
            if (any(greaterThan(scattering, vec3(0.0))))
                radiance += exp(-tau) * mediaInScattering(r.origin + t * r.direction, xw, r.direction) *
                            (dt * oneMinusExpOverX(stepTau));
            tau += stepTau;
        }
    }
    imageStore(scatteringOut, pixel, roundedToHalf(vec4(clampRadiance(radiance), 1.0)));
    imageStore(depthOut, pixel, mediaStoredDepth(mediaOpticalDepth(ow, ww, r.end)));
}
