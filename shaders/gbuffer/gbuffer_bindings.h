// G-buffer module: binding points, attribute/uniform locations and the light layout,
// shared by src/gbuffer/*.cpp and shaders/gbuffer/*.glsl.
#ifndef OBSCURA_GBUFFER_BINDINGS_H
#define OBSCURA_GBUFFER_BINDINGS_H

#include "../common/bindings_preamble.h"
#include "../common/common_bindings.h"

OBSCURA_SHADER_BEGIN

// Vertex attributes: the mesh cache's (common_bindings.h).
#define GBUFFER_ATTRIB_POSITION OBSCURA_ATTRIB_POSITION
#define GBUFFER_ATTRIB_NORMAL OBSCURA_ATTRIB_NORMAL
#define GBUFFER_ATTRIB_TEXCOORD OBSCURA_ATTRIB_TEXCOORD

// Per-draw uniforms (explicit locations).
#define GBUFFER_LOC_MODEL_VIEW 0
#define GBUFFER_LOC_NORMAL_MATRIX 1
#define GBUFFER_LOC_ALBEDO 2
#define GBUFFER_LOC_EMISSION 3
#define GBUFFER_LOC_LIGHT_COUNT 4
#define GBUFFER_LOC_WORLD_TO_VIEW 5
#define GBUFFER_LOC_NORMAL_DEVIATION 6 // normals.comp.glsl

#define GBUFFER_ALBEDO_TEXTURE_UNIT 0
#define GBUFFER_DEPTH_TEXTURE_UNIT 1
#define GBUFFER_NORMAL_TEXTURE_UNIT 2
#define GBUFFER_LIGHTS_SSBO_BINDING 0
#define GBUFFER_NEAR_PLANE_SSBO 1 // normals.comp.glsl with COUNT_NEAR_PLANE
#define GBUFFER_OUTPUT_IMAGE_UNIT 0
#define GBUFFER_WORKGROUP_SIZE 8

#define GBUFFER_LIGHT_POINT 0
#define GBUFFER_LIGHT_SPOT 1
#define GBUFFER_LIGHT_DIRECTIONAL 2
#define GBUFFER_LIGHT_RECT 3
#define GBUFFER_LIGHT_SPHERE 4

// One light in view space (std430).
struct LightData {
    vec3 position; // view space, world units
    float type;    // GBUFFER_LIGHT_*
    vec3 direction; // unit direction the light travels / rect normal (view space)
    float radius;   // world units
    vec3 radiance;  // colour * intensity (W/sr; W/m^2 directional; W/(sr m^2) rect, sphere)
    float pad0;
    float cosInner;
    float cosOuter;
    float shadowRecord; // index of the light's ShadowParams record, or -1
    float pad1;
    vec3 halfWidthAxis; // rect: the width axis times half the width (view space)
    float halfHeight;   // rect
};

#ifdef __cplusplus
static_assert(sizeof(LightData) == 80, "LightData must match std430");
#endif

OBSCURA_SHADER_END

#endif
