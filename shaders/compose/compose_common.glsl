#include "../common/math.glsl"
#include "compose_bindings.h"

layout(std140, binding = COMPOSE_PARAMS_UBO_BINDING) uniform ComposeBlock {
    ComposeParams compose;
};

// Rec. 709 / sRGB luminance of linear RGB.
float luminanceOf(vec3 c) { return dot(c, vec3(0.2126, 0.7152, 0.0722)); }
