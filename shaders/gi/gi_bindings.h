// One-bounce indirect light: binding points and the parameter block, shared by
// src/gi/*.cpp and shaders/gi/*.glsl.
#ifndef OBSCURA_GI_BINDINGS_H
#define OBSCURA_GI_BINDINGS_H

#ifdef __cplusplus
#include <glm/glm.hpp>
namespace obscura::shader {
using vec4 = glm::vec4;
using ivec4 = glm::ivec4;
using mat4 = glm::mat4;
#endif

#include "../visibility/visibility_bindings.h" // the G-buffer's depth and normal units

#define GI_PARAMS_UBO_BINDING 4
#define GI_RADIANCE_UNIT 10 // the G-buffer's direct radiance
#define GI_ALBEDO_UNIT 11   // the G-buffer's albedo
#define GI_OUT_IMAGE 0      // rgba16f, at the GI resolution
#define GI_GUIDE_OUT_IMAGE 2 // rgba32f: view normal xyz, view z (0 = background), for the filters

#define GI_METHOD_SCREEN 0
#define GI_METHOD_HYBRID 1

#define GI_WORKGROUP 8

struct GiParams {
    vec4 shape;       // x: radius, y: thickness, z: voxel start offset (view units), w: unused
    ivec4 counts;     // x: rays, y: steps, z: 1 = write the guide (the result is filtered), w: unused
    ivec4 sizes;      // x, y: GI resolution; z: scale (1, 2, 4); w: unused
    mat4 viewToVoxel; // Hybrid: view space to voxel coordinates
};

#ifdef __cplusplus
static_assert(sizeof(GiParams) == 3 * 16 + 64, "GiParams must match std140");
} // namespace obscura::shader
#endif

#endif
