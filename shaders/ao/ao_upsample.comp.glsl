// Joint bilateral upsampling to the G-buffer's resolution: the four AO pixels around each
// G-buffer pixel, weighted bilinearly and by how close their view depth and normal are to
// the pixel's own (the same weights as the blur). Where no neighbour is similar, the one
// nearest in depth is taken.
#include "../common/math.glsl"
#include "../visibility/screen_march.glsl"
#include "ao_common.glsl"

layout(local_size_x = AO_WORKGROUP, local_size_y = AO_WORKGROUP) in;
layout(binding = AO_INPUT_UNIT) uniform sampler2D aoIn;
layout(binding = AO_BENT_INPUT_UNIT) uniform sampler2D bentIn;
layout(binding = AO_GUIDE_UNIT) uniform sampler2D guide;
layout(binding = AO_OUT_IMAGE, r16f) writeonly uniform image2D aoOut;
layout(binding = AO_BENT_OUT_IMAGE, rgba16f) writeonly uniform image2D bentOut;

void main() {
    const ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(pixel, frameSize()))) return;
    const float depth = texelFetch(visDepth, pixel, 0).r;
    const vec4 normalTexel = texelFetch(visNormal, pixel, 0);
    if (isBackground(depth) || normalTexel.a == 0.0) {
        imageStore(aoOut, pixel, vec4(1.0));
        if (aoBent()) imageStore(bentOut, pixel, vec4(0.0));
        return;
    }
    const float z = viewZFromDepth(depth);
    const vec3 n = normalTexel.xyz;
    // AO pixel i covers G-buffer pixels [i s, i s + s) and was computed at i s.
    const vec2 at = vec2(pixel) / float(aoScale());
    const ivec2 base = ivec2(floor(at));
    const vec2 f = at - vec2(base);
    float sum = 0.0, total = 0.0, nearest = 1.0, nearestDz = 1e30;
    vec3 bent = vec3(0.0), nearestBent = n;
    for (int i = 0; i < 4; ++i) {
        const ivec2 o = ivec2(i & 1, i >> 1);
        const ivec2 q = clamp(base + o, ivec2(0), aoSize() - 1);
        const vec4 g = texelFetch(guide, q, 0);
        if (g.w == 0.0) continue;
        const float bilinear = (o.x == 1 ? f.x : 1.0 - f.x) * (o.y == 1 ? f.y : 1.0 - f.y);
        const float dz = (g.w - z) / (ao.blur.x * abs(z));
        const float w = bilinear * exp(-0.5 * dz * dz) * aoNormalWeight(n, g.xyz);
        const float value = texelFetch(aoIn, q, 0).r;
        const vec3 b = aoBent() ? texelFetch(bentIn, q, 0).xyz : vec3(0.0);
        sum += w * value;
        bent += w * b;
        total += w;
        if (abs(g.w - z) < nearestDz) {
            nearestDz = abs(g.w - z);
            nearest = value;
            nearestBent = b;
        }
    }
    const bool weighted = total > 1e-6;
    imageStore(aoOut, pixel, vec4(clamp(weighted ? sum / total : nearest, 0.0, 1.0)));
    if (aoBent()) imageStore(bentOut, pixel, vec4(safeNormalize(weighted ? bent : nearestBent, n), 1.0));
}
