// Compose (combine, tone mapping, output): binding points and the parameter block, shared
// by src/compose/*.cpp and shaders/compose/*.glsl.
#ifndef OBSCURA_COMPOSE_BINDINGS_H
#define OBSCURA_COMPOSE_BINDINGS_H

#ifdef __cplusplus
#include <glm/glm.hpp>
namespace obscura::shader {
using vec4 = glm::vec4;
using ivec4 = glm::ivec4;
#endif

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
    vec4 ambient;  // rgb: L_amb; w: indirect scale k
    vec4 tone;     // x: exposure, y: Drago L_wmax (0: measured), z: Drago bias, w: Drago L_dmax
    vec4 display;  // x: gamma (when not sRGB), y: the clear depth, z: DepthReconstruction::farthestDepth, w: unused
    ivec4 flags;   // x: formula, y: tone mapper, z: sRGB (0/1), w: COMPOSE_HAS_*
    ivec4 size;    // x, y: pixels; z, w: unused
};

#ifdef __cplusplus
static_assert(sizeof(ComposeParams) == 80, "ComposeParams must match std140");
} // namespace obscura::shader
#endif

#endif
