// Screen-space visibility: the texture units its GLSL functions read and the batch query
// bindings, shared by the modules that include shaders/visibility/screen_march.glsl and
// their host code.
#ifndef OBSCURA_VISIBILITY_BINDINGS_H
#define OBSCURA_VISIBILITY_BINDINGS_H

#define VIS_DEPTH_UNIT 5      // the G-buffer's hardware depth (sampler2D, texelFetch)
#define VIS_NORMAL_UNIT 6     // the G-buffer's view-space geometric normal (alpha: 0 on background, else the normal error scale)
#define VIS_BACK_DEPTH_UNIT 7 // the second depth layer (SCREEN_PEELED)
#define VIS_HIZ_UNIT 8        // the min/max view-z pyramid (SCREEN_MARCH = VIS_MARCH_HIZ), RG32F with mips

// Marching permutations (the SCREEN_MARCH define of screen_march.glsl).
#define VIS_MARCH_VIEW 0    // 3D samples in view space
#define VIS_MARCH_TEXTURE 1 // 2D samples in texture space, perspective-correct view z
#define VIS_MARCH_HIZ 2     // the texture-space samples, skipped in bulk through the pyramid

// Batch queries and the pyramid build.
#define VIS_SEGMENTS_SSBO 0
#define VIS_RESULTS_SSBO 1
#define VIS_HIZ_READ_IMAGE 0
#define VIS_HIZ_WRITE_IMAGE 1
#define VIS_LOC_STEPS 0
#define VIS_LOC_JITTER 1
#define VIS_LOC_THICKNESS 2
#define VIS_LOC_COUNT 3
#define VIS_LOC_FIRST 4
#define VIS_LOC_LEVEL 5
#define VIS_WORKGROUP_1D 64
#define VIS_WORKGROUP_2D 8

#endif
