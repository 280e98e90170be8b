// Geometry-aware separable blur at the AO resolution (one direction per dispatch): a
// Gaussian over `blurRadius` taps each side, each tap weighted by how close its view depth
// (relative) and its normal are to the centre's, so occlusion does not bleed across edges.
#include "../common/math.glsl"
#include "ao_common.glsl"

layout(local_size_x = AO_WORKGROUP, local_size_y = AO_WORKGROUP) in;
layout(binding = AO_INPUT_UNIT) uniform sampler2D aoIn;
layout(binding = AO_BENT_INPUT_UNIT) uniform sampler2D bentIn;
layout(binding = AO_GUIDE_UNIT) uniform sampler2D guide;
layout(binding = AO_OUT_IMAGE, r16f) writeonly uniform image2D aoOut;
layout(binding = AO_BENT_OUT_IMAGE, rgba16f) writeonly uniform image2D bentOut;
layout(location = AO_LOC_DIRECTION) uniform ivec2 direction;

// The joint weight of a sample with guide g against the centre's guide c (view normal xyz,
// view z; z = 0 marks background, which weighs nothing).
float guideWeight(vec4 c, vec4 g) {
    if (g.w == 0.0) return 0.0;
    const float dz = (g.w - c.w) / (ao.blur.x * abs(c.w));
    return exp(-0.5 * dz * dz) * aoNormalWeight(c.xyz, g.xyz);
}

void main() {
    const ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(pixel, aoSize()))) return;
    const vec4 c = texelFetch(guide, pixel, 0);
    const float centre = texelFetch(aoIn, pixel, 0).r;
    const vec4 centreBent = aoBent() ? texelFetch(bentIn, pixel, 0) : vec4(0.0);
    if (c.w == 0.0) { // background: nothing to blur
        imageStore(aoOut, pixel, vec4(centre));
        if (aoBent()) imageStore(bentOut, pixel, centreBent);
        return;
    }
    const int taps = ao.sizes.w;
    const float sigma = max(0.5 * float(taps), 0.5);
    float sum = centre, total = 1.0;
    vec3 bent = centreBent.xyz;
    for (int k = -taps; k <= taps; ++k) {
        if (k == 0) continue;
        const ivec2 q = pixel + k * direction;
        if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, aoSize()))) continue;
        const float w = exp(-0.5 * float(k * k) / (sigma * sigma)) * guideWeight(c, texelFetch(guide, q, 0));
        sum += w * texelFetch(aoIn, q, 0).r;
        if (aoBent()) bent += w * texelFetch(bentIn, q, 0).xyz;
        total += w;
    }
    imageStore(aoOut, pixel, vec4(clamp(sum / total, 0.0, 1.0)));
    if (aoBent()) imageStore(bentOut, pixel, vec4(safeNormalize(bent, c.xyz), 1.0));
}
