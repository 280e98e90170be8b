// media.bounded.interval: each fragment is a crossing of a pixel's view ray (through its
// centre, as the march's) with a light's volume; the nearest and farthest view depth per
// pixel are kept by atomic min and max on their float bits (non-negative floats order as
// their bits do). Drawn with depth clamping: crossings before the near plane count too. Each
// is widened by the depth's change across the pixel: the rasterizer snaps vertices to its
// sub-pixel grid, which moves a triangle seen edge-on by far more than float rounding.
#include "media_bindings.h"

in vec3 viewPosition;
layout(binding = MEDIA_NEAR_IMAGE, r32ui) coherent uniform uimage2D nearestCrossing;
layout(binding = MEDIA_FAR_IMAGE, r32ui) coherent uniform uimage2D farthestCrossing;

// The bits of max(d, 0) as a non-negative float (+0 for -0: its sign bit would win the max).
uint depthBits(float d) { return d > 0.0 ? floatBitsToUint(d) : 0u; }

void main() {
    const float depth = -viewPosition.z, spread = fwidth(depth);
    const ivec2 pixel = ivec2(gl_FragCoord.xy);
    imageAtomicMin(nearestCrossing, pixel, depthBits(depth - spread));
    imageAtomicMax(farthestCrossing, pixel, depthBits(depth + spread));
}
