// Compose (combine, tone mapping, output): binding points and the parameter block, shared
// by src/compose/*.cpp and shaders/compose/*.glsl.
#ifndef OBSCURA_COMPOSE_BINDINGS_H
#define OBSCURA_COMPOSE_BINDINGS_H

#include "../common/bindings_preamble.h"

OBSCURA_SHADER_BEGIN

#define COMPOSE_PARAMS_UBO_BINDING 5
#define COMPOSE_DIRECT_UNIT 0
#define COMPOSE_ALBEDO_UNIT 1
#define COMPOSE_AO_UNIT 2
#define COMPOSE_INDIRECT_UNIT 3
#define COMPOSE_RADIANCE_UNIT 4
#define COMPOSE_SOURCE_UNIT 5      // drawToHost
#define COMPOSE_DEPTH_UNIT 6
#define COMPOSE_RADIANCE_IMAGE 0   // rgba16f
#define COMPOSE_DISPLAY_IMAGE 1    // rgba8
#define COMPOSE_LUMINANCE_SSBO 0   // uint: the largest luminance's float bits

#define COMPOSE_FORMULA_THESIS 0
#define COMPOSE_FORMULA_PHYSICAL 1
#define COMPOSE_FORMULA_STANDARD 2
#define COMPOSE_TONE_NONE 0
#define COMPOSE_TONE_DRAGO 1
#define COMPOSE_TONE_ACES 2
#define COMPOSE_HAS_AO 1
#define COMPOSE_HAS_INDIRECT 2

#define COMPOSE_LOC_SOURCE_CHANNELS 0 // drawToHost: 1 = replicate red

#define COMPOSE_WORKGROUP 8

struct ComposeParams {
    vec3 ambient;        // L_amb, W/(sr m^2)
    float indirectScale; // k
    float exposure;
    float dragoMaxLuminance; // L_wmax; 0: measured
    float dragoBias;
    float dragoDisplayMax;   // L_dmax, cd/m^2
    float gamma;             // when not sRGB
    float clearDepth;        // DepthReconstruction::clearDepth
    float farthestDepth;     // DepthReconstruction::farthestDepth
    float pad0;
    int formula;    // COMPOSE_FORMULA_*
    int toneMapper; // COMPOSE_TONE_*
    int srgb;       // 0 or 1
    int inputs;     // COMPOSE_HAS_*
    ivec2 size;     // pixels
    int pad1;
    int pad2;
};

#ifdef __cplusplus
static_assert(sizeof(ComposeParams) == 80, "ComposeParams must match std140");
#endif

OBSCURA_SHADER_END

#endif
