// Reflective shadow map of a spot or directional light: depth as the plain depth pass, plus
// the world position for the fragment shader.
#include "shadow_bindings.h"

layout(location = SHADOW_ATTRIB_POSITION) in vec3 inPosition;
layout(location = SHADOW_LOC_MODEL_LIGHT_CLIP) uniform mat4 modelToLightClip;
layout(location = SHADOW_LOC_RSM_MODEL) uniform mat4 modelToWorld;

out vec3 vWorld;

void main() {
    gl_Position = modelToLightClip * vec4(inPosition, 1.0);
    vWorld = (modelToWorld * vec4(inPosition, 1.0)).xyz;
}
