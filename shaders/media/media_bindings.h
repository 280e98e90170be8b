// Participating media: binding points and parameter blocks, shared by src/media/*.cpp and
// shaders/media/*.glsl.
#ifndef OBSCURA_MEDIA_BINDINGS_H
#define OBSCURA_MEDIA_BINDINGS_H

#include "../common/bindings_preamble.h"

OBSCURA_SHADER_BEGIN

#define MEDIA_PARAMS_UBO_BINDING 8
#define MEDIA_DEPTH_UNIT 5        // the G-buffer's hardware depth (texelFetch)
#define MEDIA_TABLE_UNIT 1        // TABLE: G(u, v) / (e^2 / (e + u)) (src/media/airlight_table.hpp), R32F, texelFetch
#define MEDIA_FROXEL_READ_UNIT 2  // froxel resolve: the integrated grid (linear)
#define MEDIA_LIT_UNIT 2          // apply: the lit frame
#define MEDIA_SCATTERING_UNIT 3   // apply: in-scattered radiance
#define MEDIA_OPTICAL_DEPTH_UNIT 4 // apply: optical depth
#define MEDIA_GUIDE_IMAGE 4    // rgba32f, GUIDE: (0, 0, 1, view z) for the filters (src/filters/guided_filters.hpp)
#define MEDIA_OUT_IMAGE 0          // rgba16f: in-scattered radiance (or the applied frame, or a froxel grid)
#define MEDIA_DEPTH_OUT_IMAGE 1    // rgba16f: optical depth per channel (or the froxel grid's)

// Bounded marching (media_volume.*.glsl): the shadow volumes' vertices, and the nearest and
// farthest view depth where each pixel's ray crosses them (float bits, atomic min and max).
#define MEDIA_VOLUME_SSBO 3
#define MEDIA_NEAR_IMAGE 2 // r32ui
#define MEDIA_FAR_IMAGE 3  // r32ui
#define MEDIA_CELLS_IMAGE 4 // r32f: each cell's farthest depth (media_volume.comp.glsl)
#define MEDIA_VOLUME_LOC_GRID 0 // ivec4: shadow record, texels per cell, cells per side, first vertex
#define MEDIA_VOLUME_LOC_CAP 1  // float: distance along the spot's axis of cells whose map holds nothing

#define MEDIA_MAX_MEDIA 8
#define MEDIA_WORKGROUP 8
#define MEDIA_FROXEL_WORKGROUP 4

#define MEDIA_DENSITY_CONSTANT 0
#define MEDIA_DENSITY_HEIGHT 1
#define MEDIA_DENSITY_GRID 2 // the grid at MEDIA_GRID_UNIT (one per run)
#define MEDIA_GRID_UNIT 6

#define MEDIA_PHASE_ISOTROPIC 0
#define MEDIA_PHASE_HG 1
#define MEDIA_PHASE_RAYLEIGH 2
#define MEDIA_PHASE_SCHLICK 3

// One homogeneous medium in a box, axis-aligned in world space: rays are taken to world
// space (viewToWorld) to meet it.
struct MediumData {
    vec3 boxMin;     // world units
    float phase;     // MEDIA_PHASE_*
    vec3 boxMax;     // world units
    float g;         // HG g, or Schlick's k
    vec3 scattering; // sigma_s at density 1, 1/world unit
    float density;   // MEDIA_DENSITY_*
    vec3 extinction; // sigma_t = sigma_s + sigma_a at density 1, 1/world unit
    float heightFalloff; // MEDIA_DENSITY_HEIGHT: 1/world unit
};

struct MediaParams {
    MediumData media[MEDIA_MAX_MEDIA];
    mat4 viewToWorld;
    int mediumCount;
    int lightCount;
    int steps;         // march samples, quadrature nodes, or froxel slices
    int jitter;        // 1: per-pixel offset of the march's samples
    ivec2 size;        // output pixels
    ivec2 tableSize;   // TABLE: texels along u and v
    ivec3 froxels;     // froxel grid: tiles x, y and slices
    float froxelRange; // froxel: view distance the last slice ends at, world units
    float tableMaxU;   // TABLE: u of its last column
    int densitySteps;  // midpoint steps of a grid medium's optical depth along a segment
    int scale;         // raymarch, bounded: the G-buffer's resolution over the march's (1, 2 or 4)
    float backgroundZ; // GUIDE: the view z the guide gives background pixels (< 0)
};

OBSCURA_SHADER_END

#endif
