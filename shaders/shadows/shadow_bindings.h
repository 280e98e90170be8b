// Shadow maps: binding points and the mask pass's parameter block, shared by
// src/shadows/*.cpp and shaders/shadows/*.glsl.
#ifndef OBSCURA_SHADOW_BINDINGS_H
#define OBSCURA_SHADOW_BINDINGS_H

#include "../common/bindings_preamble.h"

#include "../common/common_bindings.h"
#include "../visibility/visibility_bindings.h" // the G-buffer's depth and normal units

OBSCURA_SHADER_BEGIN

#define SHADOW_ATTRIB_POSITION OBSCURA_ATTRIB_POSITION
#define SHADOW_LOC_MODEL_LIGHT_CLIP 0 // depth pass: model -> light clip (paraboloid: -> the map's frame)
#define SHADOW_LOC_PARABOLOID_DEPTH 1 // paraboloid depth pass: (a, b, 2 / resolution), window depth b / distance - a
#define SHADOW_LOC_RSM_MODEL 2  // reflective pass: model -> world
#define SHADOW_LOC_RSM_ALBEDO 3 // the mesh's material albedo
#define SHADOW_LOC_RSM_LIGHT 4  // spot position or directional direction (world), w: SHADOW_LIGHT_*
#define SHADOW_LOC_RSM_POWER 5  // color * intensity, w: texel side (see shadow_rsm.frag.glsl)
#define SHADOW_LOC_RSM_SPOT 6   // spot axis (world, unit)
#define SHADOW_LOC_RSM_CONE 7   // spot cos(inner), cos(outer)
#define SHADOW_LIGHTS_SSBO 4 // ShadowParams per mapped light (shadow_sample.glsl)
#define SHADOW_RANGE_SSBO 5  // depth_range.comp.glsl: nearest and farthest view distance, float bits
#define SHADOW_MAP_UNIT 9     // sampler2DArrayShadow, one layer per map (bound with its sampler by every reader)
#define SHADOW_MOMENTS_UNIT 10 // sampler2DArray of the moment filters, linear
#define SHADOW_DEPTH_READ_UNIT 11 // the maps as plain sampler2DArray (moments pass, PCSS blocker search)
#define SHADOW_MOMENTS_IMAGE 1  // rgba32f image2DArray written by the moments and blur passes
#define SHADOW_MOMENTS_READ_IMAGE 2
#define SHADOW_LOC_FILTER_PARAMS 0 // moments pass: x exponent +, y exponent -; blur: x radius, y direction
#define SHADOW_LOC_LAYER_RANGE 1   // moments pass: first layer, layers
#define SHADOW_MASK_IMAGE 0  // r16f output
#define SHADOW_WORKGROUP 8
#define SHADOW_MAX_CASCADES 4
#define SHADOW_MAX_MAPS 6 // per light: cascades, or the faces of a cube

#define SHADOW_LIGHT_SPOT 0
#define SHADOW_LIGHT_DIRECTIONAL 1
#define SHADOW_LIGHT_POINT 2
#define SHADOW_LIGHT_RECT 3 // mapped like a point light, by one paraboloid over its front side

#define SHADOW_PCF_GRID 0
#define SHADOW_PCF_POISSON 1
#define SHADOW_PCF_OPTIMIZED 2 // the grid's weights from (r + 1)^2 bilinear comparisons
#define SHADOW_POISSON_TAPS 16
#define SHADOW_PCSS_MAX_RADIUS 128 // texels: the widest PCSS search and kernel

#define SHADOW_FILTER_HARD 0
#define SHADOW_FILTER_PCF 1
#define SHADOW_FILTER_VSM 2   // moments (t, t^2)
#define SHADOW_FILTER_ESM 3   // c t, filtered in log space
#define SHADOW_FILTER_EVSM2 4 // (e^(c+ t'), e^(2 c+ t')), t' = 2 t - 1
#define SHADOW_FILTER_EVSM4 5 // and (-e^(-c- t'), e^(-2 c- t'))
#define SHADOW_FILTER_MSM 6   // (t, t^2, t^3, t^4), Hamburger 4MSM
#define SHADOW_FILTER_PCSS 7  // blocker search, then a Poisson-disc PCF as wide as the penumbra
#define SHADOW_FILTER_MOMENTS(f) ((f) >= SHADOW_FILTER_VSM && (f) <= SHADOW_FILTER_MSM)

struct ShadowCascade {
    mat4 viewToLight; // G-buffer view space -> the map's clip space (paraboloid: the map's frame)
    float sliceEnd;   // far end of the slice (view distance, world units)
    // Texel side at the map: orthographic, world units; perspective, per unit distance;
    // paraboloid, 2 / resolution.
    float texelSize;
    float layer;
    float projection;  // 0 orthographic, 1 perspective, 2 paraboloid
    vec4 depthMapping; // ShadowMapInfo::depthMapping: a, b, near, far
};
// (A cube's faces are "cascades" too: +x, -x, +y, -y, +z, -z of world space.)

// One mapped light, as shadow_sample.glsl reads it (std430 and std140 agree: vec4 and mat4 only).
struct ShadowParams {
    ShadowCascade cascades[SHADOW_MAX_MAPS];
    vec3 light;      // view-space position, or (directional) unit direction toward the light
    float lightType; // SHADOW_LIGHT_*
    vec3 spotAxis;      // view-space unit axis the spot (rect: its normal) points along
    float spotCosOuter; // cos(outer angle) (rect: 0)
    float constantBias; // world units
    float slopeBias;    // texels
    float normalOffset; // texels
    float cascadeBlend; // fraction of the slice
    float minVariance;
    float lightBleedReduction;
    float exponent;         // c+
    float negativeExponent; // c-
    float contactLength;    // world units; 0: off
    float contactSteps;
    float contactThickness; // world units
    float firstSliceStart;  // directional: where the first cascade's slice begins (view distance)
    int mapCount;      // cascades or 6 faces
    int receiverPlane; // 0 or 1
    int pcfRadius;
    int resolution;    // texels per side
    float pcfKernel;       // SHADOW_PCF_*
    float lightRadius;     // world units
    float pcssSearchScale; // blocker search radius in light radii at the receiver, (1 - f) / f
    float pad0;
    vec4 poisson[SHADOW_POISSON_TAPS / 2]; // the Poisson disc's points in the unit disc, two per vec4
};

#ifndef __cplusplus
// Storage of the moment filters' maps: 32F, or with ShadowMomentPrecision::Bits16 half floats
// (MOMENTS_HALF: VSM, ESM, EVSM) or 16-bit UNORM in an optimized basis (MOMENTS_UNORM: MSM).
#if defined(MOMENTS_UNORM)
#define SHADOW_MOMENT_FORMAT rgba16
#elif defined(MOMENTS_HALF)
#define SHADOW_MOMENT_FORMAT rgba16f
#else
#define SHADOW_MOMENT_FORMAT rgba32f
#endif
// EVSM's largest exponent: e^(2 c) must stay finite in the moments' storage (32F: 3.4e38,
// 16F: 65504, so c <= ln(65504) / 2 = 5.54).
#ifdef MOMENTS_HALF
#define SHADOW_EVSM_MAX_EXPONENT 5.54
#else
#define SHADOW_EVSM_MAX_EXPONENT 42.0
#endif
#endif

#ifdef __cplusplus
static_assert(sizeof(ShadowParams) == SHADOW_MAX_MAPS * 96 + 7 * 16 + SHADOW_POISSON_TAPS * 8, "ShadowParams must match std140");
#endif

OBSCURA_SHADER_END

#endif
