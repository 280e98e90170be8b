// Geometry-aware separable blur at the reduced resolution (one direction per dispatch): a
// Gaussian over `taps` samples each side, each weighted by how close its view depth and its
// normal are to the centre's (guideWeight), so values do not bleed across edges.
//
// Background pixels (guide z = 0) are neither read nor written: no tap reads them, so the
// horizontal pass leaves them out of its temporary, and the vertical pass leaves the value
// the integrator wrote there (TILES: the tiles pass's clear, as the integrator skips them).
// MODULATE: the vertical pass of a full-resolution blur, the last step (filter_common.glsl).
// TILES: one group per tile with geometry
// (geometry_tiles.glsl); every pixel a tap reads lies in one, the rest are background.
//! variant: RGB
//! variant: RGB MODULATE
//! variant: DIRECTION
//! variant: TILES
//! variant: RGB TILES
//! variant: DIRECTION TILES
#include "filter_common.glsl"
#include "geometry_tiles.glsl"

layout(local_size_x = FILTER_WORKGROUP, local_size_y = FILTER_WORKGROUP) in;
layout(location = FILTER_LOC_STEP) uniform ivec2 stepDirection;

void main() {
#ifdef TILES
    const ivec2 pixel = tiledPixel();
#else
    const ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
#endif
    if (any(greaterThanEqual(pixel, filterLowSize()))) return;
    const vec4 c = imageLoad(guideIn, pixel);
    if (c.w == 0.0) return;
    const int taps = filterParams.blurTaps;
    const float sigma = max(0.5 * float(taps), 0.5);
    const FILTER_VALUE centre = loadValue(pixel);
    FILTER_VALUE offsets = FILTER_VALUE(0.0); // sum of w (value - centre), see weightedMean
#ifdef DIRECTION
    vec3 offset = directionOffset(pixel, c.xyz); // summed as `offsets` is
#endif
    float total = 1.0;
    for (int k = -taps; k <= taps; ++k) {
        const ivec2 q = pixel + k * stepDirection;
        if (k == 0 || !insideLow(q)) continue;
        const vec4 g = imageLoad(guideIn, q);
        if (g.w == 0.0) continue;
        const float w = exp2(-0.5 * kLog2E * float(k * k) / (sigma * sigma) + guideLog2Weight(c.xyz, c.w, g.xyz, g.w));
        offsets += w * (loadValue(q) - centre);
#ifdef DIRECTION
        offset += w * directionOffset(q, g.xyz);
#endif
        total += w;
    }
    imageStore(valueOut, pixel, vec4(filterFinish(modulated(pixel, weightedMean(centre, offsets, total)))));
#ifdef DIRECTION
    imageStore(directionOut, pixel, vec4(directionFromOffset(c.xyz, offset / total), 1.0));
#endif
}
