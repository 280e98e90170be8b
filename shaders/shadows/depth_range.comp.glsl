// The nearest and farthest view distance (-z) of the G-buffer's geometry pixels, as float
// bits (positive floats order like their bits): a min and a max per workgroup in shared
// memory, then one atomic each into the result. Background pixels are skipped.
#include "../common/depth.glsl"
#include "shadow_bindings.h"

layout(local_size_x = SHADOW_WORKGROUP, local_size_y = SHADOW_WORKGROUP) in;
layout(binding = VIS_DEPTH_UNIT) uniform sampler2D visDepth;
layout(std430, binding = SHADOW_RANGE_SSBO) buffer DepthRange {
    uint nearestBits;
    uint farthestBits;
};

shared uint groupNearest, groupFarthest;

void main() {
    if (gl_LocalInvocationIndex == 0u) {
        groupNearest = 0x7f800000u; // +inf
        groupFarthest = 0u;
    }
    barrier();
    const ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (all(lessThan(pixel, frameSize()))) {
        const float depth = texelFetch(visDepth, pixel, 0).r;
        const float distance = isBackground(depth) ? 0.0 : -viewZFromDepth(depth);
        if (distance > 0.0 && !isinf(distance)) {
            atomicMin(groupNearest, floatBitsToUint(distance));
            atomicMax(groupFarthest, floatBitsToUint(distance));
        }
    }
    barrier();
    if (gl_LocalInvocationIndex == 0u && groupFarthest != 0u) {
        atomicMin(nearestBits, groupNearest);
        atomicMax(farthestBits, groupFarthest);
    }
}
