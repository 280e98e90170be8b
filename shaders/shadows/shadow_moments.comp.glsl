// Moments of one light's shadow maps for the moment filters: per texel the distance t in
// [0, 1] between the map's near and far planes, turned into the FILTER's moments.
//! variant: FILTER=2
//! variant: FILTER=3
//! variant: FILTER=4
//! variant: FILTER=5
//! variant: FILTER=6
//! variant: FILTER=4 MOMENTS_HALF
//! variant: FILTER=6 MOMENTS_UNORM
#include "shadow_bindings.h"
#ifndef FILTER
#define FILTER SHADOW_FILTER_VSM // a moment filter: the pass exists only for them
#endif
#include "shadow_sample.glsl"

layout(local_size_x = SHADOW_WORKGROUP, local_size_y = SHADOW_WORKGROUP) in;
layout(binding = SHADOW_DEPTH_READ_UNIT) uniform sampler2DArray depthMaps;
layout(binding = SHADOW_MOMENTS_IMAGE, SHADOW_MOMENT_FORMAT) writeonly uniform image2DArray momentsOut;
layout(location = SHADOW_LOC_LAYER_RANGE) uniform ivec2 layers; // first layer of the light, maps

void main() {
    const ivec3 texel = ivec3(gl_GlobalInvocationID.xy, int(gl_GlobalInvocationID.z));
    if (any(greaterThanEqual(texel.xy, ivec2(shadowLights[0].resolution))) || texel.z >= layers.y) return;
    const float d = texelFetch(depthMaps, ivec3(texel.xy, layers.x + texel.z), 0).r;
    imageStore(momentsOut, ivec3(texel.xy, layers.x + texel.z), shadowMomentsOf(shadowLinear(0, texel.z, d), 0));
}
