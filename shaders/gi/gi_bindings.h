// One-bounce indirect light: binding points and the parameter block, shared by
// src/gi/*.cpp and shaders/gi/*.glsl.
#ifndef OBSCURA_GI_BINDINGS_H
#define OBSCURA_GI_BINDINGS_H

#include "../common/bindings_preamble.h"

#include "../visibility/visibility_bindings.h" // the G-buffer's depth and normal units

OBSCURA_SHADER_BEGIN

#define GI_PARAMS_UBO_BINDING 4
#define GI_RADIANCE_UNIT 10 // the G-buffer's direct radiance
#define GI_ALBEDO_UNIT 11   // the G-buffer's albedo
#define GI_OUT_IMAGE 0      // rgba16f, at the GI resolution
#define GI_GUIDE_OUT_IMAGE 2 // rgba32f: view normal xyz, view z (0 = background), for the filters

#define GI_METHOD_SCREEN 0
#define GI_METHOD_HYBRID 1

#define GI_WORKGROUP 8

struct GiParams {
    float radius;           // world = view units
    float thickness;        // world units
    float voxelStartOffset; // Hybrid: how far rays start off the surface, view units
    float pad0;
    int rayCount;
    int stepCount;
    int writeGuide; // 1: the result is filtered, so the guide is written
    int pad1;
    ivec2 size; // the GI resolution, pixels
    int scale;  // G-buffer pixels per GI pixel: 1, 2 or 4
    int pad2;
    mat4 viewToVoxel; // Hybrid: view space to voxel coordinates
};

#ifdef __cplusplus
static_assert(sizeof(GiParams) == 3 * 16 + 64, "GiParams must match std140");
#endif

OBSCURA_SHADER_END

#endif
