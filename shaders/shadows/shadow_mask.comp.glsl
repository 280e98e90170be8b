// The shadow mask of one light at the G-buffer's samples: per pixel the fraction of the
// filter's depth comparisons that find the biased receiver lit (see shadow_maps.hpp); the
// light is record 0 of SHADOW_LIGHTS_SSBO.
//! variant: FILTER=0
//! variant: FILTER=1
//! variant: FILTER=2
//! variant: FILTER=3
//! variant: FILTER=4
//! variant: FILTER=5
//! variant: FILTER=6
//! variant: FILTER=7
//! variant: FILTER=5 MOMENTS_HALF
//! variant: FILTER=6 MOMENTS_UNORM
#include "../visibility/screen_march.glsl"
#include "shadow_sample.glsl"

layout(local_size_x = SHADOW_WORKGROUP, local_size_y = SHADOW_WORKGROUP) in;
layout(binding = SHADOW_MASK_IMAGE, r16f) writeonly uniform image2D maskOut;

void main() {
    const ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(pixel, frameSize()))) return;
    const float depth = texelFetch(visDepth, pixel, 0).r;
    const vec4 normalTexel = texelFetch(visNormal, pixel, 0);
    float v = 1.0;
    if (!isBackground(depth) && normalTexel.a != 0.0) {
        const vec3 p = viewPositionFromDepth(pixelCenterUv(pixel), depth);
        const vec3 n = safeNormalize(normalTexel.xyz, viewDirectionTo(p));
        v = shadowVisibility(0, p, n);
        // Contact shadows: a short screen-space ray toward the light from the receiver lifted
        // off its surface by a texel (so that its own plane does not hide it).
        const float contactLength = shadowLights[0].contactLength;
        if (contactLength > 0.0 && v > 0.0) {
            const vec3 start = p + n * shadowTexel(0, p, 0);
            const bool directional = shadowLightType(0) == SHADOW_LIGHT_DIRECTIONAL;
            const float reach = directional ? contactLength : min(contactLength, length(shadowLights[0].light - start));
            const float hit = screenMarch(ScreenRayStart(start, n, storedNormalError(normalTexel)), shadowToLight(0, p), reach, int(shadowLights[0].contactSteps), 0.5,
                                         shadowLights[0].contactThickness);
            v = hit >= 0.0 ? 0.0 : v;
        }
    }
    imageStore(maskOut, pixel, vec4(clamp(v, 0.0, 1.0)));
}
