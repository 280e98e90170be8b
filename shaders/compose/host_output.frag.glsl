// The source texture over the host's viewport; one-channel sources replicated to RGB.
#include "compose_bindings.h"

in vec2 vUv;
layout(binding = COMPOSE_SOURCE_UNIT) uniform sampler2D source;
layout(location = COMPOSE_LOC_SOURCE_CHANNELS) uniform int sourceChannels;
layout(location = 0) out vec4 color;

void main() {
    const vec4 s = texture(source, vUv);
    color = vec4(sourceChannels == 1 ? s.rrr : s.rgb, 1.0);
}
