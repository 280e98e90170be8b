// The tiles with geometry: squares of FILTER_WORKGROUP x FILTER_WORKGROUP low-resolution
// pixels (scale times as many G-buffer pixels each way) with at least one G-buffer pixel that
// is not background, listed by geometry_tiles.comp.glsl. With TILES the passes at the reduced
// resolution (the integrator, the blur) run one group per listed tile, the integrator's
// invocations on the tile's pixels with geometry only (tiledGeometryPixel), and the
// upsampling (scale / 2)^2 groups of quads, all dispatched indirectly from the header; the
// images' other texels keep the background values they were cleared to.
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
                            // listing) a mark per tile; then two uints per tile, its
                            // pixelMask (geometry_tiles.comp.glsl)
};

ivec2 listedTile(uint i) {
    const uint code = tileCodes[i];
    return ivec2(code & 0xFFFFu, code >> 16);
}

// The low-resolution pixel of this invocation of a group per listed tile.
ivec2 tiledPixel() { return listedTile(gl_WorkGroupID.x) * FILTER_WORKGROUP + ivec2(gl_LocalInvocationID.xy); }

// The tiles' grid for a G-buffer of `gbufferSize` pixels at `scale`.
ivec2 tileGrid(ivec2 gbufferSize, int scale) {
    const int side = FILTER_WORKGROUP * scale; // in G-buffer pixels
    return (gbufferSize + side - 1) / side;
}

// Where tile `index` (row by row) keeps its pixel mask: after the codes and the marks.
uint pixelMaskSlot(uint index, uint tiles) { return 2u * tiles + 2u * index; }

// The number of the n-th (from 0) set bit of `word` (31 when it has n or fewer): a binary
// search on the bit counts of its halves.
uint nthSetBit(uint word, uint n) {
    uint first = 0u;
    for (int width = 16; width > 0; width >>= 1) {
        const uint below = uint(bitCount(bitfieldExtract(word, int(first), width)));
        if (n >= below) {
            n -= below;
            first += uint(width);
        }
    }
    return first;
}

// The integrator's pixel for invocation k (its place in its 8 x 8 group) of a group per
// listed tile: the k-th of the tile's low-resolution pixels whose block's top-left G-buffer
// pixel has depth, in row order; false for the invocations past them.
// Why not tiledPixel(): on llvmpipe an 8-lane batch runs its loops as long as its slowest
// lane, so a batch with one pixel of a thin object among background costs as much as a full
// one. Packed, a tile's pixels fill the first batches and the rest run only the straight-line
// code (on a GPU: fewer, fuller warps). At 128 x 128 the half-resolution integrators took
// 0.56-0.94 of the time they took on tiledPixel() (31 of 32 rows on the four models, medians of
// paired runs; benchmarks/README.md).
// The mask, not a compaction in shared memory: that one's two barriers a group made the
// integrator 40 % slower on the Cornell box at 512 x 512, every tile full.
bool tiledGeometryPixel(ivec2 gbufferSize, int scale, uint k, out ivec2 pixel) {
    const ivec2 tile = listedTile(gl_WorkGroupID.x), grid = tileGrid(gbufferSize, scale);
    const uint slot = pixelMaskSlot(uint(tile.y * grid.x + tile.x), uint(grid.x * grid.y));
    const uvec2 mask = uvec2(tileCodes[slot], tileCodes[slot + 1u]);
    const uint inLow = uint(bitCount(mask.x)), inBoth = inLow + uint(bitCount(mask.y));
    const uint index = k < inLow ? nthSetBit(mask.x, k) : 32u + nthSetBit(mask.y, k - inLow);
    pixel = tile * FILTER_WORKGROUP + ivec2(index % uint(FILTER_WORKGROUP), index / uint(FILTER_WORKGROUP));
    return k < inBoth;
}

// The quad (2 x 2 G-buffer pixels, in quads) of this invocation of the upsampling: a tile holds
// 4 scale quads each way, FILTER_WORKGROUP per group, the group's place in the tile being
// gl_WorkGroupID.yz.
ivec2 tiledQuad(int scale) {
    const ivec2 group = ivec2(gl_WorkGroupID.yz);
    return (listedTile(gl_WorkGroupID.x) * (scale / 2) + group) * FILTER_WORKGROUP + ivec2(gl_LocalInvocationID.xy);
}
#endif // TILES
#endif
