// Shared between C++ and GLSL: binding points and the per-frame uniform block layout.
// Every member is a vec4/ivec4/mat4 so that std140 and the C++ layout agree.
#ifndef OBSCURA_COMMON_BINDINGS_H
#define OBSCURA_COMMON_BINDINGS_H

#ifdef __cplusplus
#include <glm/glm.hpp>
namespace obscura::shader {
using vec4 = glm::vec4;
using ivec4 = glm::ivec4;
using mat4 = glm::mat4;
#endif

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
    vec4 depthXY;     // DepthReconstruction: xyScale.xy, xyOffset.xy
    vec4 depthZ;      // DepthReconstruction: zScale, zBiasHi, zBiasLo, clearDepth
    ivec4 viewport;   // width, height (pixels), projection kind, reversed-Z (0/1)
    vec4 depthPrecision; // x: the depth buffer's step, 1 / (2^bits - 1) fixed point, 0 float;
                         // y: GBufferView::normalError of the normals read;
                         // z: DepthReconstruction::farthestDepth
    vec4 sampleShift;    // xyz: the frame's shift of every pixel's sample rotation (xy) and
                         // jitter (z) in [0, 1) (sampling.glsl); 0 for frame index 0
};

#ifdef __cplusplus
static_assert(sizeof(FrameData) == 3 * 64 + 5 * 16, "FrameData must match std140");
} // namespace obscura::shader
#endif

#endif
