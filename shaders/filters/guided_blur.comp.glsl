// Geometry-aware separable blur at the reduced resolution (one direction per dispatch): a
// Gaussian over `taps` samples each side, each weighted by how close its view depth and its
// normal are to the centre's (guideWeight), so values do not bleed across edges.
//! variant: RGB
#include "filter_common.glsl"

layout(local_size_x = FILTER_WORKGROUP, local_size_y = FILTER_WORKGROUP) in;
layout(binding = FILTER_GUIDE_UNIT) uniform sampler2D guide;
layout(binding = FILTER_VALUE_UNIT) uniform sampler2D valueIn;
layout(binding = FILTER_DIRECTION_UNIT) uniform sampler2D directionIn;
layout(binding = FILTER_VALUE_IMAGE, FILTER_FORMAT) writeonly uniform image2D valueOut;
layout(binding = FILTER_DIRECTION_IMAGE, rgba16f) writeonly uniform image2D directionOut;
layout(location = FILTER_LOC_STEP) uniform ivec2 stepDirection;

void main() {
    const ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(pixel, filterLowSize()))) return;
    const vec4 c = texelFetch(guide, pixel, 0);
    const FILTER_VALUE centre = FILTER_FETCH(valueIn, pixel);
    const vec4 centreDirection = filterHasDirection() ? texelFetch(directionIn, pixel, 0) : vec4(0.0);
    if (c.w == 0.0) { // background: nothing to blur
        imageStore(valueOut, pixel, vec4(centre));
        if (filterHasDirection()) imageStore(directionOut, pixel, centreDirection);
        return;
    }
    const int taps = filterParams.sizes.w;
    const float sigma = max(0.5 * float(taps), 0.5);
    FILTER_VALUE sum = centre;
    vec3 direction = centreDirection.xyz;
    float total = 1.0;
    for (int k = -taps; k <= taps; ++k) {
        const ivec2 q = pixel + k * stepDirection;
        if (k == 0 || any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, filterLowSize()))) continue;
        const vec4 g = texelFetch(guide, q, 0);
        if (g.w == 0.0) continue;
        const float w = exp(-0.5 * float(k * k) / (sigma * sigma)) * guideWeight(c.xyz, c.w, g.xyz, g.w);
        sum += w * FILTER_FETCH(valueIn, q);
        if (filterHasDirection()) direction += w * texelFetch(directionIn, q, 0).xyz;
        total += w;
    }
    imageStore(valueOut, pixel, vec4(filterFinish(sum / total)));
    if (filterHasDirection()) imageStore(directionOut, pixel, vec4(safeNormalize(direction, c.xyz), 1.0));
}
