// Ambient occlusion and obscurance: binding points and the parameter block, shared by
// src/ao/*.cpp and shaders/ao/*.glsl.
#ifndef OBSCURA_AO_BINDINGS_H
#define OBSCURA_AO_BINDINGS_H

#include "../common/bindings_preamble.h"

#include "../visibility/visibility_bindings.h" // the G-buffer's depth and normal units

OBSCURA_SHADER_BEGIN

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
    float radius;           // world = view units
    float thickness;        // world units
    float voxelStartOffset; // Voxel: how far rays start off the surface, view units
    float pad0;
    int rayCount;
    int stepCount;
    int flags;   // AO_FLAG_*
    int falloff; // AO_FALLOFF_*
    ivec2 size;  // the AO resolution, pixels
    int scale;   // G-buffer pixels per AO pixel: 1, 2 or 4
    int pad1;
    mat4 viewToVoxel; // Voxel: view space to voxel coordinates
};

#ifdef __cplusplus
static_assert(sizeof(AoParams) == 3 * 16 + 64, "AoParams must match std140");
#endif

OBSCURA_SHADER_END

#endif
