// media.raymarch: single scattering along each pixel's view ray by marching `steps` samples
// over the part of it inside the media (first entry to last exit, up to the surface), each
// step jittered per pixel and integrated with the energy-conserving step (Hillaire 2015):
//   L += T(0, t) Sum_lights sigma_s p L_i T(t, light) V(t) * dt (1 - exp(-sigma_t dt)) / (sigma_t dt)
// so that a dense medium tends to sigma_s/sigma_t times the source, never beyond it. T toward
// the lights is exact per box; V comes from the shadow maps (SHADOWS). The optical depth
// stored is the view ray's exact one (the boxes' lengths times sigma_t), whatever the steps.
// At reduced resolution (MediaSettings::resolution) the march runs per reduced pixel and the
// optical depth per G-buffer pixel (OPTICAL_DEPTH); the filters blur and upsample the rest.
//! Every permutation the module compiles (validated by glslangValidator at build time):
//! variant:
//! variant: SHADOWS
//! variant: SHADOWS BOUNDED
//! variant: GUIDE
//! variant: SHADOWS GUIDE
//! variant: SHADOWS BOUNDED GUIDE
//! variant: OPTICAL_DEPTH
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
#ifdef GUIDE
layout(binding = MEDIA_GUIDE_IMAGE, rgba32f) writeonly uniform image2D guideOut;
#endif

#ifdef BOUNDED
// media.bounded: every light is a mapped spot whose volume (media_volume.*.glsl) the pass
// drew; its lit points lie between the ray's first and last crossing of the volumes, or from
// the ray's origin where that lies inside one's frustum (the volume there may hold it).
layout(binding = MEDIA_NEAR_IMAGE, r32ui) readonly uniform uimage2D nearestCrossing;
layout(binding = MEDIA_FAR_IMAGE, r32ui) readonly uniform uimage2D farthestCrossing;

bool mediaInsideFrustum(vec3 x) {
    for (int i = 0; i < media.lightCount; ++i) {
        const int k = int(lights[i].shadowRecord);
        const vec4 c = shadowMapCoord(k, x, 0);
        if (c.w > 0.0 && all(greaterThanEqual(c.xy, vec2(0.0))) && all(lessThanEqual(c.xy, vec2(1.0)))) return true;
    }
    return false;
}

// The part of `span` (distances along r) where the ray may be lit; empty (x >= y) if none.
// Crossings are view depths: t = depth / -direction.z (the ray starts at view z = 0). The
// interpolated depths are widened by 1e-4 of themselves for their rounding.
vec2 mediaLitSpan(ivec2 pixel, MediaRay r, vec2 span) {
    const float nearest = uintBitsToFloat(imageLoad(nearestCrossing, pixel).r);
    const float farthest = uintBitsToFloat(imageLoad(farthestCrossing, pixel).r);
    const float perDepth = 1.0 / max(-r.direction.z, 1e-30);
    const bool inside = mediaInsideFrustum(r.origin);
    const bool crossed = nearest <= farthest;
    if (!inside && !crossed) return vec2(0.0);
    const float from = inside ? 0.0 : nearest * (1.0 - 1e-4) * perDepth;
    const float to = crossed ? farthest * (1.0 + 1e-4) * perDepth : span.y;
    return vec2(max(span.x, from), min(span.y, to));
}
#endif

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

// The march along view ray r of G-buffer pixel `pixel`.
vec3 mediaMarch(ivec2 pixel, MediaRay r, vec3 ow, vec3 ww) {
#ifdef BOUNDED
    const vec2 span = mediaLitSpan(pixel, r, mediaSpan(ow, ww, r.end));
#else
    const vec2 span = mediaSpan(ow, ww, r.end);
#endif
    vec3 radiance = vec3(0.0);
    if (span.y > span.x) {
        const float dt = (span.y - span.x) / float(media.steps);
        const float jitter = media.jitter != 0 ? pixelJitter(pixel, frame.sampleShift) : 0.5;
        // From the camera to the current step's start (0 before the first medium's entry).
        vec3 tau = mediaOpticalDepth(ow, ww, span.x);
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
    return radiance;
}

#ifdef OPTICAL_DEPTH
// A march at reduced resolution: the optical depth of every G-buffer pixel, on its own.
void main() {
    const ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(pixel, frameSize()))) return;
    const MediaRay r = mediaViewRay(pixel, texelFetch(depthTexture, pixel, 0).r);
    imageStore(depthOut, pixel, mediaStoredDepth(mediaOpticalDepth(mediaToWorld(r.origin), mediaDirectionToWorld(r.direction), r.end)));
}
#else
// Output pixel `target` marches G-buffer pixel out * scale (the filters' convention: a reduced
// pixel covers [i s, i s + s) and is computed at i s). At full resolution it also stores the
// optical depth; GUIDE: the filters' guide, (0, 0, 1, view z), background at media.backgroundZ.
void main() {
    const ivec2 target = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(target, media.size))) return;
    const ivec2 pixel = target * media.scale;
    const float depth = texelFetch(depthTexture, pixel, 0).r;
    const MediaRay r = mediaViewRay(pixel, depth);
    const vec3 ow = mediaToWorld(r.origin), ww = mediaDirectionToWorld(r.direction);
    imageStore(scatteringOut, target, roundedToHalf(vec4(clampRadiance(mediaMarch(pixel, r, ow, ww)), 1.0)));
    if (media.scale == 1) imageStore(depthOut, pixel, mediaStoredDepth(mediaOpticalDepth(ow, ww, r.end)));
#ifdef GUIDE
    const float z = isBackground(depth) ? media.backgroundZ : viewZFromDepth(depth);
    imageStore(guideOut, target, vec4(0.0, 0.0, 1.0, z));
#endif
}
#endif
