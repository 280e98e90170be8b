// Media::apply: the lit frame seen through the media, L = L_lit exp(-tau) + L_s, per channel
// (lit alpha kept).
#include "../common/math.glsl"
#include "media_bindings.h"

layout(local_size_x = MEDIA_WORKGROUP, local_size_y = MEDIA_WORKGROUP, local_size_z = 1) in;
layout(location = 0) uniform ivec2 size;
layout(binding = MEDIA_LIT_UNIT) uniform sampler2D litTexture;
layout(binding = MEDIA_SCATTERING_UNIT) uniform sampler2D scatteringTexture;
layout(binding = MEDIA_OPTICAL_DEPTH_UNIT) uniform sampler2D depthTexture;
layout(binding = MEDIA_OUT_IMAGE, rgba16f) writeonly uniform image2D appliedOut;

void main() {
    const ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(pixel, size))) return;
    const vec4 lit = texelFetch(litTexture, pixel, 0);
    const vec3 tau = texelFetch(depthTexture, pixel, 0).rgb;
    const vec3 scattered = texelFetch(scatteringTexture, pixel, 0).rgb;
    // A NaN or Inf in the host's frame stays out of the result: clampRadiance maps it.
    const vec3 through = clampRadiance(lit.rgb) * exp(-tau);
    imageStore(appliedOut, pixel, roundedToHalf(vec4(clampRadiance(through + scattered), isnan(lit.a) ? 1.0 : lit.a)));
}
