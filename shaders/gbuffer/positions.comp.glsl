// Writes reconstructed view-space positions (debug/test output of GBuffer::positions).
#include "../common/depth.glsl"
#include "gbuffer_bindings.h"

layout(local_size_x = GBUFFER_WORKGROUP_SIZE, local_size_y = GBUFFER_WORKGROUP_SIZE) in;
layout(binding = GBUFFER_DEPTH_TEXTURE_UNIT) uniform sampler2D depthTexture;
layout(binding = GBUFFER_OUTPUT_IMAGE_UNIT, rgba32f) writeonly uniform image2D positions;

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(pixel, frameSize()))) return;
    float depth = texelFetch(depthTexture, pixel, 0).r;
    vec4 result = vec4(0.0);
    if (!isBackground(depth)) result = vec4(viewPositionFromDepth(pixelCenterUv(pixel), depth), 1.0);
    imageStore(positions, pixel, result);
}
