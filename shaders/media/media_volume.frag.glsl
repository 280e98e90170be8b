// media.bounded.interval: each fragment is a crossing of a pixel's view ray (through its
// centre, as the march's) with a light's volume; the nearest and farthest view depth per
// pixel are kept by atomic min and max on their float bits (non-negative floats order as
// their bits do). Drawn with depth clamping: crossings before the near plane count too.
#include "media_bindings.h"

in vec3 viewPosition;
layout(binding = MEDIA_NEAR_IMAGE, r32ui) coherent uniform uimage2D nearestCrossing;
layout(binding = MEDIA_FAR_IMAGE, r32ui) coherent uniform uimage2D farthestCrossing;

void main() {
    const uint depth = floatBitsToUint(max(-viewPosition.z, 0.0));
    const ivec2 pixel = ivec2(gl_FragCoord.xy);
    imageAtomicMin(nearestCrossing, pixel, depth);
    imageAtomicMax(farthestCrossing, pixel, depth);
}
