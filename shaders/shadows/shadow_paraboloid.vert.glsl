// Depth from a point light into one paraboloid map: positions in the map's frame (the light
// at the origin, the map's axis +z); the geometry shader clips and projects them.
#include "shadow_bindings.h"

layout(location = SHADOW_ATTRIB_POSITION) in vec3 inPosition;
layout(location = SHADOW_LOC_MODEL_LIGHT_CLIP) uniform mat4 modelToMap;

out vec3 vMap;

void main() { vMap = (modelToMap * vec4(inPosition, 1.0)).xyz; }
