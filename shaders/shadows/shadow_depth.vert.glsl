// Depth from a light: positions only, no attributes beyond them.
#include "shadow_bindings.h"

layout(location = SHADOW_ATTRIB_POSITION) in vec3 inPosition;
layout(location = SHADOW_LOC_MODEL_LIGHT_CLIP) uniform mat4 modelToLightClip;

void main() { gl_Position = modelToLightClip * vec4(inPosition, 1.0); }
