// Shared between C++ and GLSL: binding points and the per-frame uniform block layout
// (written as bindings_preamble.h says, so that std140 and the C++ layout agree).
#ifndef OBSCURA_COMMON_BINDINGS_H
#define OBSCURA_COMMON_BINDINGS_H

#include "../common/bindings_preamble.h"

OBSCURA_SHADER_BEGIN

#define OBSCURA_FRAME_UBO_BINDING 0

// The tiled random texture of sampling.glsl (RG32F, OBSCURA_NOISE_SIZE^2 texels), on a
// texture unit no module uses for anything else.
#define OBSCURA_NOISE_TEXTURE_UNIT 15
#define OBSCURA_NOISE_SIZE 64

// Vertex attributes of every mesh Obscura draws (core/mesh_cache builds the VAOs).
#define OBSCURA_ATTRIB_POSITION 0
#define OBSCURA_ATTRIB_NORMAL 1
#define OBSCURA_ATTRIB_TEXCOORD 2

// Integrators that run their rays in batches (shaders/common/ray_batch.glsl): the partial
// sums, and the uniform with the batch's range and flags.
#define OBSCURA_RAY_BATCH_SSBO 7
#define OBSCURA_LOC_RAY_BATCH 0

#define OBSCURA_PROJECTION_PERSPECTIVE 0
#define OBSCURA_PROJECTION_ORTHOGRAPHIC 1

struct FrameData {
    mat4 view;        // world -> view
    mat4 projection;  // view -> clip
    mat4 viewInverse; // view -> world
    // DepthReconstruction (camera.hpp): view rays and window depth -> view z
    vec2 rayScale;
    vec2 rayOffset;
    float depthScale;
    float depthBiasHi;
    float depthBiasLo;
    float clearDepth;
    ivec2 size;         // pixels
    int projectionKind; // OBSCURA_PROJECTION_*
    int reversedZ;      // 0 or 1
    float depthStep;     // the depth buffer's step: 1 / (2^bits - 1) fixed point, 0 float
    float normalError;   // GBufferView::normalError of the normals read
    float farthestDepth; // DepthReconstruction::farthestDepth
    float pad0;
    // The frame's shift of every pixel's sample rotation (xy) and jitter (z) in [0, 1)
    // (sampling.glsl); 0 for frame index 0.
    vec3 sampleShift;
    float pad1;
};

#ifdef __cplusplus
static_assert(sizeof(FrameData) == 3 * 64 + 5 * 16, "FrameData must match std140");
#endif

OBSCURA_SHADER_END

#endif
