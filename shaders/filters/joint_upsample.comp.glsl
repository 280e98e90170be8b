// Joint bilateral upsampling to the G-buffer's resolution: the four low-resolution pixels
// around each G-buffer pixel, weighted bilinearly and by guideWeight against the pixel's own
// view depth and normal. Where no neighbour is similar, the one nearest in depth is taken.
// Background pixels get the background value (and no direction).
//! variant: RGB
#include "../visibility/screen_march.glsl"
#include "filter_common.glsl"

layout(local_size_x = FILTER_WORKGROUP, local_size_y = FILTER_WORKGROUP) in;
layout(binding = FILTER_GUIDE_UNIT) uniform sampler2D guide;
layout(binding = FILTER_VALUE_UNIT) uniform sampler2D valueIn;
layout(binding = FILTER_DIRECTION_UNIT) uniform sampler2D directionIn;
layout(binding = FILTER_VALUE_IMAGE, FILTER_FORMAT) writeonly uniform image2D valueOut;
layout(binding = FILTER_DIRECTION_IMAGE, rgba16f) writeonly uniform image2D directionOut;

void main() {
    const ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(pixel, frameSize()))) return;
    const float depth = texelFetch(visDepth, pixel, 0).r;
    const vec4 normalTexel = texelFetch(visNormal, pixel, 0);
    if (isBackground(depth) || normalTexel.a == 0.0) {
        imageStore(valueOut, pixel, vec4(filterParams.weights.z));
        if (filterHasDirection()) imageStore(directionOut, pixel, vec4(0.0));
        return;
    }
    const float z = viewZFromDepth(depth);
    const vec3 n = normalTexel.xyz;
    // Low-resolution pixel i covers G-buffer pixels [i s, i s + s) and was computed at i s.
    const vec2 at = vec2(pixel) / float(filterScale());
    const ivec2 base = ivec2(floor(at));
    const vec2 f = at - vec2(base);
    FILTER_VALUE sum = FILTER_VALUE(0.0), nearest = FILTER_VALUE(filterParams.weights.z);
    vec3 direction = vec3(0.0), nearestDirection = n;
    float total = 0.0, nearestDz = 1e30;
    for (int i = 0; i < 4; ++i) {
        const ivec2 o = ivec2(i & 1, i >> 1);
        const ivec2 q = clamp(base + o, ivec2(0), filterLowSize() - 1);
        const vec4 g = texelFetch(guide, q, 0);
        if (g.w == 0.0) continue;
        const float bilinear = (o.x == 1 ? f.x : 1.0 - f.x) * (o.y == 1 ? f.y : 1.0 - f.y);
        const float w = bilinear * guideWeight(n, z, g.xyz, g.w);
        const FILTER_VALUE value = FILTER_FETCH(valueIn, q);
        const vec3 d = filterHasDirection() ? texelFetch(directionIn, q, 0).xyz : vec3(0.0);
        sum += w * value;
        direction += w * d;
        total += w;
        if (abs(g.w - z) < nearestDz) {
            nearestDz = abs(g.w - z);
            nearest = value;
            nearestDirection = d;
        }
    }
    const bool weighted = total > 1e-6;
    imageStore(valueOut, pixel, vec4(filterFinish(weighted ? sum / total : nearest)));
    if (filterHasDirection())
        imageStore(directionOut, pixel, vec4(safeNormalize(weighted ? direction : nearestDirection, n), 1.0));
}
