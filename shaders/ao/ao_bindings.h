// Ambient occlusion and obscurance: binding points and the parameter block, shared by
// src/ao/*.cpp and shaders/ao/*.glsl.
#ifndef OBSCURA_AO_BINDINGS_H
#define OBSCURA_AO_BINDINGS_H

#ifdef __cplusplus
#include <glm/glm.hpp>
namespace obscura::shader {
using vec4 = glm::vec4;
using ivec4 = glm::ivec4;
using mat4 = glm::mat4;
#endif

#include "../visibility/visibility_bindings.h" // the G-buffer's depth and normal units

#define AO_PARAMS_UBO_BINDING 2
#define AO_OUT_IMAGE 0       // r16f, at the AO resolution
#define AO_BENT_OUT_IMAGE 1  // rgba16f
#define AO_GUIDE_OUT_IMAGE 2 // rgba32f: view normal xyz, view z (0 = background), for the filters

#define AO_METHOD_RAYMARCH 0
#define AO_METHOD_POINTS 1
#define AO_METHOD_HORIZON 2
#define AO_METHOD_VOXEL 3

#define AO_FALLOFF_NONE 0
#define AO_FALLOFF_LINEAR 1
#define AO_FALLOFF_QUADRATIC 2
#define AO_FALLOFF_SMOOTH 3

#define AO_FLAG_COSINE 1
#define AO_FLAG_BENT 2
#define AO_FLAG_GUIDE 4 // write the guide: the result is blurred or upsampled

#define AO_WORKGROUP 8

struct AoParams {
    vec4 shape;       // x: radius, y: thickness (world = view units), z: voxel start offset (view units), w: unused
    ivec4 counts;     // x: rays, y: steps, z: flags (AO_FLAG_*), w: falloff (AO_FALLOFF_*)
    ivec4 sizes;      // x, y: AO resolution; z: scale (1, 2, 4); w: unused
    vec4 unused;
    mat4 viewToVoxel; // Voxel: view space to voxel coordinates
    ivec4 voxel;      // x: traversal (VOXEL_METHOD_*), y, z, w: unused
};

#ifdef __cplusplus
static_assert(sizeof(AoParams) == 4 * 16 + 64 + 16, "AoParams must match std140");
} // namespace obscura::shader
#endif

#endif
