// The tiles with geometry: squares of FILTER_WORKGROUP x FILTER_WORKGROUP low-resolution
// pixels (scale times as many G-buffer pixels each way) with at least one G-buffer pixel that
// is not background, listed by geometry_tiles.comp.glsl. With TILES the passes at the reduced
// resolution (the integrator, the blur) run one group per listed tile and the upsampling
// (scale / 2)^2 groups of quads, all dispatched indirectly from the header; the images'
// other texels keep the background values they were cleared to.
//
// Why: on llvmpipe every SIMD batch runs a shader's straight-line code, and the first pass of
// every loop, whether or not any lane is active (benchmarks/README.md), so a background pixel
// costs a filter pass as much as a surface pixel does.
//
// Included unconditionally, its content guarded by TILES: the shader library expands each file
// once, at its first #include, whatever #if encloses it.
#ifndef OBSCURA_GEOMETRY_TILES_GLSL
#define OBSCURA_GEOMETRY_TILES_GLSL
#include "filter_bindings.h"
#ifdef TILES

// Read-only but in the pass that lists them.
#ifndef GEOMETRY_TILES_ACCESS
#define GEOMETRY_TILES_ACCESS readonly restrict
#endif
layout(std430, binding = FILTER_TILES_SSBO) GEOMETRY_TILES_ACCESS buffer GeometryTiles {
    uint tileGroups[3];     // glDispatchComputeIndirect's arguments: (tiles listed, 1, 1)
    uint tileQuadGroups[3]; // the upsampling's: (tiles listed, scale / 2, scale / 2)
    uint tileGroupsDone;    // geometry_tiles.comp.glsl: the groups that have marked their tiles
    uint tileUnused;
    uint tileCodes[];       // x | y << 16, in tiles, listed in row order; then (while
                            // listing) a mark per tile, geometry_tiles.comp.glsl
};

ivec2 listedTile(uint i) {
    const uint code = tileCodes[i];
    return ivec2(code & 0xFFFFu, code >> 16);
}

// The low-resolution pixel of this invocation of a group per listed tile.
ivec2 tiledPixel() { return listedTile(gl_WorkGroupID.x) * FILTER_WORKGROUP + ivec2(gl_LocalInvocationID.xy); }

// The quad (2 x 2 G-buffer pixels, in quads) of this invocation of the upsampling: a tile holds
// 4 scale quads each way, FILTER_WORKGROUP per group, the group's place in the tile being
// gl_WorkGroupID.yz.
ivec2 tiledQuad(int scale) {
    const ivec2 group = ivec2(gl_WorkGroupID.yz);
    return (listedTile(gl_WorkGroupID.x) * (scale / 2) + group) * FILTER_WORKGROUP + ivec2(gl_LocalInvocationID.xy);
}
#endif // TILES
#endif
