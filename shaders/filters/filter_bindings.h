// Geometry-aware filters (separable blur at a reduced resolution, joint bilateral
// upsampling): binding points and the parameter block, shared by src/filters/ and
// shaders/filters/. The guide image holds (view normal xyz, view z; z = 0: background) per
// low-resolution pixel, written by the integrator that produced the values.
#ifndef OBSCURA_FILTER_BINDINGS_H
#define OBSCURA_FILTER_BINDINGS_H

#include "../common/bindings_preamble.h"

OBSCURA_SHADER_BEGIN

// The low-resolution images are read with imageLoad, not texelFetch: the same texels, and on
// llvmpipe (Mesa 22.3) a small fraction of the cost. Measured there at 512x512, 21 loads of
// RGBA32F per pixel: 1.3 ms with imageLoad against 5.0 ms with texelFetch (glFinish wall
// clock). GPUs read both through the same texture path.
#define FILTER_PARAMS_UBO_BINDING 3
#define FILTER_VALUE_IMAGE 0         // written: the value (r16f, or rgba16f with RGB)
#define FILTER_DIRECTION_IMAGE 1     // written: the direction (rgba16f), with DIRECTION
#define FILTER_GUIDE_IN_IMAGE 2      // read: the guide (rgba32f)
#define FILTER_VALUE_IN_IMAGE 3      // read: the value
#define FILTER_DIRECTION_IN_IMAGE 4  // read: the direction, with DIRECTION
#define FILTER_TILES_SSBO 5          // the tiles with geometry (geometry_tiles.glsl), with TILES
#define FILTER_REFINE_SSBO 6         // the pixels to refine (refine_list.glsl), with REFINE
#define FILTER_MODULATE_UNIT 12      // read: a G-buffer-sized factor of the last step's rgb, with MODULATE

// Temporal accumulation (temporal.comp.glsl), at the G-buffer's resolution.
#define TEMPORAL_PARAMS_UBO_BINDING 6
#define TEMPORAL_VALUE_IMAGE 0            // read and written in place: the result (r16f, or rgba16f with RGB)
#define TEMPORAL_HISTORY_OUT_IMAGE 1      // written: the new history (rgba16f: value, a = frames in it)
#define TEMPORAL_GEOMETRY_OUT_IMAGE 2     // written: the new history's geometry (rg32ui)
#define TEMPORAL_HISTORY_IMAGE 3          // read: the last frame's history (rgba16f)
#define TEMPORAL_GEOMETRY_IMAGE 4         // read: its geometry (rg32ui: view depth's float bits, octahedral world normal)

#define FILTER_LOC_STEP 0 // blur: ivec2 pixel step of this pass
#define FILTER_LOC_TILE_SCALE 1 // geometry_tiles.comp.glsl: int scale to the full resolution, 2 or 4

#define FILTER_FLAG_UNIT_RANGE 2 // values are clamped to [0, 1]

#define FILTER_WORKGROUP 8
// Invocations per group of the refinement dispatch: the integrators' 8 x 8 workgroups.
#define FILTER_REFINE_GROUP 64
// The refinement list's header: an indirect dispatch (groups x, y, z), then the count.
#define FILTER_REFINE_HEADER_UINTS 4
// The tile list's header: two indirect dispatches (groups x, y, z), one group per listed tile
// at the low resolution, then scale / 2 x scale / 2 groups of the upsampling's quads per tile
// (y, z: the group's place in the tile); the count of marking groups that are done
// (geometry_tiles.comp.glsl), and one unused, padding the header to 32 bytes.
#define FILTER_TILES_HEADER_UINTS 8

struct FilterParams {
    ivec2 lowSize; // the low resolution, pixels
    int scale;     // to the full resolution: 1, 2 or 4
    int blurTaps;  // each side
    float depthSigma;      // relative view depth weighted e^-1/2
    float normalPower;
    float background;      // the value of background pixels
    float refineThreshold; // REFINE: the share of the bilinear weight
    int flags;             // FILTER_FLAG_*
    float backgroundZ;     // 0, or the view z background pixels stand at (GuidedFilterSettings)
    int pad1;
    int pad2;
};

struct TemporalParams {
    mat4 previousView;           // world -> the last frame's view
    mat4 previousViewProjection; // world -> the last frame's clip space
    vec2 previousRayScale;       // the last frame's DepthReconstruction
    vec2 previousRayOffset;
    float depthTolerance;  // relative
    float normalThreshold; // cosine
    float maxFrames;
    float pad0;
    int hasHistory;          // 0 or 1
    int previousPerspective; // 0 or 1: the last frame's camera
    int pad1;
    int pad2;
};

#ifdef __cplusplus
static_assert(sizeof(TemporalParams) == 2 * 64 + 3 * 16, "TemporalParams must match std140");
static_assert(sizeof(FilterParams) == 48, "FilterParams must match std140");
#endif

OBSCURA_SHADER_END

#endif
