//! variant: HAS_NORMALS
//! variant: HAS_NORMALS HAS_TEXCOORDS ALBEDO_TEXTURE
#include "../common/frame.glsl"
#include "gbuffer_bindings.h"

layout(location = GBUFFER_ATTRIB_POSITION) in vec3 inPosition;
#ifdef HAS_NORMALS
layout(location = GBUFFER_ATTRIB_NORMAL) in vec3 inNormal;
#endif
#ifdef HAS_TEXCOORDS
layout(location = GBUFFER_ATTRIB_TEXCOORD) in vec2 inTexcoord;
#endif

layout(location = GBUFFER_LOC_MODEL_VIEW) uniform mat4 modelView;
layout(location = GBUFFER_LOC_NORMAL_MATRIX) uniform mat4 normalMatrix;

// The peeling pass must reproduce the first pass's depths bit for bit.
invariant gl_Position;

out VertexData {
    vec3 viewPosition;
    vec3 viewNormal;
    vec2 texcoord;
} vout;

void main() {
    vec4 p = modelView * vec4(inPosition, 1.0);
    vout.viewPosition = p.xyz;
#ifdef HAS_NORMALS
    vout.viewNormal = mat3(normalMatrix) * inNormal;
#else
    vout.viewNormal = vec3(0.0);
#endif
#ifdef HAS_TEXCOORDS
    vout.texcoord = inTexcoord;
#else
    vout.texcoord = vec2(0.0);
#endif
    gl_Position = frame.projection * p;
}
