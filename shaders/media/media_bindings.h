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
#define MEDIA_OUT_IMAGE 0          // rgba16f: in-scattered radiance (or the applied frame, or a froxel grid)
#define MEDIA_DEPTH_OUT_IMAGE 1    // rgba16f: optical depth per channel (or the froxel grid's)

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
    float pad3;
    float pad4;
};

OBSCURA_SHADER_END

#endif
