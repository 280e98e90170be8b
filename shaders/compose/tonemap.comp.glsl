// Tone mapping and display encoding of the combined radiance into 8-bit values.
#include "compose_common.glsl"

layout(local_size_x = COMPOSE_WORKGROUP, local_size_y = COMPOSE_WORKGROUP) in;
layout(binding = COMPOSE_RADIANCE_UNIT) uniform sampler2D radiance;
layout(binding = COMPOSE_DISPLAY_IMAGE, rgba8) writeonly uniform image2D displayOut;
layout(std430, binding = COMPOSE_LUMINANCE_SSBO) readonly buffer Luminance {
    uint maxLuminanceBits;
};

// Drago et al. 2003: L_d = (L_dmax / 100) / log10(L_wmax + 1) * ln(L + 1) /
// ln(2 + 8 (L / L_wmax)^(ln b / ln 0.5)), applied to the luminance; colour keeps its ratios.
vec3 drago(vec3 c) {
    const float lw = luminanceOf(c);
    if (!(lw > 0.0)) return vec3(0.0);
    const float measured = uintBitsToFloat(maxLuminanceBits);
    const float lmax = max(compose.tone.y > 0.0 ? compose.tone.y : measured, 1e-6);
    const float exponent = log(compose.tone.z) / log(0.5);
    const float ld = (compose.tone.w * 0.01 / log(lmax + 1.0) * log(10.0)) * log(lw + 1.0) /
                     log(2.0 + 8.0 * pow(lw / lmax, exponent));
    return c * (ld / lw);
}

// Narkowicz 2015's fit of the ACES reference rendering and output transforms.
vec3 aces(vec3 x) { return clamp(x * (2.51 * x + 0.03) / (x * (2.43 * x + 0.59) + 0.14), 0.0, 1.0); }

float srgbEncode(float x) { return x <= 0.0031308 ? 12.92 * x : 1.055 * pow(x, 1.0 / 2.4) - 0.055; }

void main() {
    const ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(pixel, compose.size.xy))) return;
    vec3 c = texelFetch(radiance, pixel, 0).rgb;
    if (compose.flags.y == COMPOSE_TONE_DRAGO) c = drago(c);
    else if (compose.flags.y == COMPOSE_TONE_ACES) c = aces(c);
    c = clamp(c, 0.0, 1.0);
    if (compose.flags.z != 0) c = vec3(srgbEncode(c.r), srgbEncode(c.g), srgbEncode(c.b));
    else c = pow(c, vec3(1.0 / compose.display.x));
    imageStore(displayOut, pixel, vec4(c, 1.0));
}
