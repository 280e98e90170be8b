// The per-frame uniform block (camera, depth reconstruction, viewport).
#include "common_bindings.h"

layout(std140, binding = OBSCURA_FRAME_UBO_BINDING) uniform FrameBlock {
    FrameData frame;
};

ivec2 frameSize() { return frame.size; }
bool isPerspective() { return frame.projectionKind == OBSCURA_PROJECTION_PERSPECTIVE; }
// GBufferView::normalError: how far the stored normals may lie from the true ones.
float storedNormalError() { return frame.normalError; }
// One pixel's bound: normalError times the normal texel's alpha (1 for our normals and a
// host's face normals; shading, bent and reconstructed normals carry their own bound there,
// normals.comp.glsl).
float storedNormalError(vec4 normalTexel) { return storedNormalError() * normalTexel.a; }
