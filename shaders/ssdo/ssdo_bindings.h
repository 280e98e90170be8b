// Screen-space directional occlusion: binding points and the parameter block, shared by
// src/ssdo/*.cpp and shaders/ssdo/*.glsl.
#ifndef OBSCURA_SSDO_BINDINGS_H
#define OBSCURA_SSDO_BINDINGS_H

#include "../common/bindings_preamble.h"

#include "../visibility/visibility_bindings.h" // the G-buffer's depth and normal units

OBSCURA_SHADER_BEGIN

#define SSDO_PARAMS_UBO_BINDING 8
#define SSDO_SENDER_UNIT 10     // bounce: the direct pass's result, the G-buffer's size
#define SSDO_ALBEDO_UNIT 11     // the G-buffer's albedo
// Not 12: the filters' modulation (FILTER_MODULATE_UNIT) stays bound there when REFINE runs.
#define SSDO_LIGHT_UNIT 4       // bounce: the G-buffer's direct radiance (its lights), when it has one
#define SSDO_OUT_IMAGE 0        // rgba16f, at the integrator's resolution
#define SSDO_GUIDE_OUT_IMAGE 2  // rgba32f: view normal xyz, view z (0 = background), for the filters

#define SSDO_PASS_DIRECT 0
#define SSDO_PASS_BOUNCE 1

#define SSDO_ENVIRONMENT_TERM_UNIT 10 // lights pass: the direct pass's result, the G-buffer's size

#define SSDO_VIEWS_UBO_BINDING 9
#define SSDO_EXTRA_DEPTH_UNIT 1  // EXTRA_VIEWS: the extra views' depth, a layer each
#define SSDO_EXTRA_NORMAL_UNIT 2 // EXTRA_VIEWS: their view-space geometric normals
#define SSDO_MAX_EXTRA_VIEWS 4

// Instant radiosity (pass ssdo.vpls): the reflective shadow maps' flux, world normal and
// world position, and the indirect light it adds to.
#define SSDO_RSM_FLUX_UNIT 1
#define SSDO_RSM_NORMAL_UNIT 2
#define SSDO_RSM_POSITION_UNIT 3
#define SSDO_INDIRECT_TERM_UNIT 10 // with BOUNCE: the bounce's result, the G-buffer's size
#define SSDO_VPLS_UBO_BINDING 9
#define SSDO_MAX_VPL_LAYERS 8

#define SSDO_WORKGROUP 8

struct SsdoParams {
    float radius;           // r_max, world = view units
    float thickness;        // world units
    float patchArea;        // bounce: A_s = pi r_max^2 / N, world units^2
    float patchSolidAngle;  // bounce: the most solid angle one patch may subtend, sr
    int rayCount;
    int stepCount;
    int writeGuide; // 1: the result is filtered, so the guide is written
    int addLight;   // bounce: 1 adds the G-buffer's direct radiance to the senders'
    ivec2 size;     // the integrator's resolution, pixels
    int scale;      // G-buffer pixels per integrator pixel: 1, 2 or 4
    float bounceStrength;
    float environmentLevel; // direct: the cube's level each sample reads
    int lightCount;         // lights pass
    float shadowCorrection; // lights pass: the march's reach in biased segments (0: none)
    float contactThickness; // lights pass: ShadowMaskSettings::contactThickness, world units
    int contactSteps;       // lights pass: ShadowMaskSettings::contactSteps
    float pad0;
    float pad1;
    float pad2;
    mat4 viewToWorld; // rotation only (directions)
};

// The extra views (EXTRA_VIEWS): each with the main camera's projection, seen from its own
// eye; their G-buffers at `size`.
struct SsdoViews {
    mat4 mainToView[SSDO_MAX_EXTRA_VIEWS]; // main view space -> the extra view's
    ivec2 size;                            // pixels
    int count;
    int pad0;
};

// The reflective shadow maps the VPLs come from: a grid of grid x grid cells in each listed
// layer, one VPL at each cell's centre texel standing for the whole cell.
struct SsdoVpls {
    ivec4 layers[SSDO_MAX_VPL_LAYERS / 4]; // RSM layers, 4 a row
    int layerCount;
    int grid;       // cells per side
    int resolution; // RSM texels per side
    int pad0;
};

#ifdef __cplusplus
static_assert(sizeof(SsdoVpls) == 2 * 16 + 16, "SsdoVpls must match std140");
static_assert(sizeof(SsdoViews) == 4 * 64 + 16, "SsdoViews must match std140");
static_assert(sizeof(SsdoParams) == 5 * 16 + 64, "SsdoParams must match std140");
#endif

OBSCURA_SHADER_END

#endif
