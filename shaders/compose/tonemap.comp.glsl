// Tone mapping and display encoding of the combined radiance into 8-bit values.
#include "compose_common.glsl"

layout(local_size_x = COMPOSE_WORKGROUP, local_size_y = COMPOSE_WORKGROUP) in;
layout(binding = COMPOSE_RADIANCE_UNIT) uniform sampler2D radiance;
layout(binding = COMPOSE_DISPLAY_IMAGE, rgba8) writeonly uniform image2D displayOut;
layout(std430, binding = COMPOSE_LUMINANCE_SSBO) readonly buffer Luminance {
    uint maxLuminanceBits;
};

// ln(1 + x) / x for x >= 0 (1 at 0), so that Drago's L_d / L needs no division by L, which
// a GPU may flush to 0 where it is subnormal (a tiny exposure). GLSL's log has an absolute
// error of up to 2^-21 near 1, which for x = 1e-6 is half of ln(1 + x), and 1 + x drops x
// below 2^-24 altogether: a dim frame's Drago mapping would be off by tens of percent. Below
// 1/16 the series to x^5 (ln(1 + x) to x^6), whose remainder (x^6 / 7) is under 2^-24, to a
// few ulp; from 1/16 up log's 2^-20 absolute, at most 1.6e-5 of the result.
float lnOnePlusOverX(float x) {
    const float series = 1.0 + x * (-1.0 / 2.0 + x * (1.0 / 3.0 + x * (-1.0 / 4.0 + x * (1.0 / 5.0 - x * (1.0 / 6.0)))));
    return x >= 0.0625 ? log(1.0 + x) / x : series;
}

// Drago et al. 2003: L_d = (L_dmax / 100) / log10(L_wmax + 1) * ln(L + 1) /
// ln(2 + 8 (L / L_wmax)^(ln b / ln 0.5)), applied to the luminance; colour keeps its ratios.
// L and L_wmax are after the exposure; a frame's own maximum is measured before it.
vec3 drago(vec3 c) {
    const float lw = luminanceOf(c);
    if (!(lw > 0.0)) return vec3(0.0);
    const float lmeasured = compose.exposure * uintBitsToFloat(maxLuminanceBits);
    // A floor far below a frame's maximum, so that a dim frame is still mapped to its own; it
    // also bounds the first factor, (L_dmax / 100) ln 10 / ln(1 + L_wmax), by 230 / 1e-30,
    // and with L <= 1e6 (exposure) * 65504 (clampRadiance) ln(1 + L) <= 25, so L_d is
    // finite. The ratio L / L_wmax is kept in [1e-30, 1e30]: a given maximum far from L could
    // take it past float's range or to 0, and at bias 1 (exponent 0) pow(inf, 0) and pow(0, 0)
    // are NaN or undefined. The clamp changes only ln(2 + 8 r^e), for pixels 1e30 times
    // brighter or darker than the maximum: with the frame's own maximum those display as 0.
    const float lmax = max(compose.dragoMaxLuminance > 0.0 ? compose.dragoMaxLuminance : lmeasured, 1e-30);
    const float exponent = log(compose.dragoBias) / log(0.5);
    const float ratio = clamp(lw / lmax, 1e-30, 1e30);
    const float firstFactor = compose.dragoDisplayMax * 0.01 * log(10.0) / (lmax * lnOnePlusOverX(lmax));
    return c * (firstFactor * lnOnePlusOverX(lw) / log(2.0 + 8.0 * pow(ratio, exponent))); // c L_d / L
}

// Narkowicz 2015's fit of the ACES reference rendering and output transforms.
vec3 aces(vec3 x) { return clamp(x * (2.51 * x + 0.03) / (x * (2.43 * x + 0.59) + 0.14), 0.0, 1.0); }

float srgbEncode(float x) { return x <= 0.0031308 ? 12.92 * x : 1.055 * pow(x, 1.0 / 2.4) - 0.055; }

void main() {
    const ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(pixel, compose.size))) return;
    vec3 c = compose.exposure * texelFetch(radiance, pixel, 0).rgb; // the exposure
    if (compose.toneMapper == COMPOSE_TONE_DRAGO) c = drago(c);
    else if (compose.toneMapper == COMPOSE_TONE_ACES) c = aces(c);
    c = clamp(c, 0.0, 1.0);
    if (compose.srgb != 0) c = vec3(srgbEncode(c.r), srgbEncode(c.g), srgbEncode(c.b));
    else c = pow(c, vec3(1.0 / compose.gamma));
    imageStore(displayOut, pixel, vec4(c, 1.0));
}
