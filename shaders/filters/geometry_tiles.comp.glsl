// Lists the tiles with geometry (geometry_tiles.glsl), in row order, in one dispatch:
// - one invocation per tile writes its pixel mask (tilePixelMask: a gather at each
//   low-resolution pixel's top-left G-buffer pixel) and marks it if any G-buffer pixel of
//   its (FILTER_WORKGROUP scale)^2 is not background (isBackground): at scale 2 those gathers
//   read them all, at 4 (when they found none) a scan of the whole tile's 2 x 2 texels per
//   textureGather follows until one is not. The passes also treat a pixel with normal
//   alpha 0 as background, so the list holds every tile that any of them computes anything
//   in, and possibly a few more;
// - the group that finishes marking last (a counter in the header) writes the marked tiles'
//   codes in row order and the dispatch headers: each invocation counts a run of marks, one
//   adds the counts up, and each writes its run's tiles from its offset.
// Why row order, not an append per tile: on llvmpipe the integrator took about 7 % longer over
// a list in the order the appends came (the Cornell box at 512 x 512, every tile listed), as
// each group's tiles came from rows the threads interleaved. Why one invocation per tile, not
// a group per tile: the groups' barriers, to combine their invocations' findings, made the
// pass cost 1.7 ms there (the two barriers here come once per 8 x 8 tiles). Why the last group
// compacts, not a second dispatch: at 128 x 128 on llvmpipe that dispatch cost 0.03-0.17 ms a
// frame, as much as the marking (benchmarks/README.md).
#include "../visibility/screen_march.glsl"
// Coherent: the last group reads the other groups' marks.
#define GEOMETRY_TILES_ACCESS coherent restrict
#define TILES
#include "geometry_tiles.glsl"

layout(location = FILTER_LOC_TILE_SCALE) uniform int tileScale;
layout(local_size_x = FILTER_WORKGROUP, local_size_y = FILTER_WORKGROUP) in;

const uint kGroupInvocations = uint(FILTER_WORKGROUP * FILTER_WORKGROUP);

shared bool lastGroup;
shared uint runOffsets[kGroupInvocations];

int tileSide() { return FILTER_WORKGROUP * tileScale; } // in G-buffer pixels
ivec2 tileCount() { return tileGrid(frameSize(), tileScale); }
uint tileTotal() { return uint(tileCount().x * tileCount().y); }
// The marks follow the codes' room: tileCodes[tileTotal() + tile index, row by row].
uint markSlot(uint index) { return tileTotal() + index; }

// The depths of the 2 x 2 G-buffer pixels from `corner`, w that of `corner` itself
// (textureGather's order). Past the image's last row or column the clamp-to-edge sampler
// repeats it, and the tile reaching past the image holds that row or column itself, so no
// tile is marked for its neighbour's geometry.
vec4 quadDepth(ivec2 corner) { return textureGather(visDepth, (vec2(corner) + 1.0) / vec2(frameSize()), 0); }

bool anyGeometry(vec4 depth) {
    return !(isBackground(depth.x) && isBackground(depth.y) && isBackground(depth.z) && isBackground(depth.w));
}

bool quadHasGeometry(ivec2 corner) { return anyGeometry(quadDepth(corner)); }

bool tileHasGeometry(ivec2 tile) {
    const int quadsPerSide = tileSide() / 2;
    const ivec2 origin = tile * tileSide();
    bool geometry = false;
    for (int i = 0; i < quadsPerSide * quadsPerSide && !geometry; ++i)
        geometry = quadHasGeometry(origin + 2 * ivec2(i % quadsPerSide, i / quadsPerSide));
    return geometry;
}

// The tile's pixel mask (tiledGeometryPixel): bit i, row by row, set where low-resolution
// pixel i has depth at its block's top-left G-buffer pixel. `geometry`: whether the gathers
// at those pixels found any; at scale 2 they read the whole tile.
uvec2 tilePixelMask(ivec2 tile, out bool geometry) {
    const ivec2 lowSize = (frameSize() + tileScale - 1) / tileScale;
    uvec2 mask = uvec2(0u);
    geometry = false;
    for (int i = 0; i < FILTER_WORKGROUP * FILTER_WORKGROUP; ++i) {
        const ivec2 low = tile * FILTER_WORKGROUP + ivec2(i % FILTER_WORKGROUP, i / FILTER_WORKGROUP);
        const vec4 depth = quadDepth(low * tileScale);
        geometry = geometry || anyGeometry(depth);
        if (all(lessThan(low, lowSize)) && !isBackground(depth.w)) mask[i / 32] |= 1u << uint(i % 32);
    }
    return mask;
}

// Whether this group is the last to have marked its tiles: every mark is then written.
bool finishedLast() {
    memoryBarrierBuffer();
    barrier();
    if (gl_LocalInvocationIndex == 0u) {
        const uint groups = gl_NumWorkGroups.x * gl_NumWorkGroups.y;
        lastGroup = atomicAdd(tileGroupsDone, 1u) == groups - 1u;
    }
    memoryBarrierShared();
    barrier();
    return lastGroup;
}

// Writes the marked tiles' codes in row order and the headers' group counts (all invocations).
void compactMarks() {
    memoryBarrierBuffer();
    const uint total = tileTotal(), run = (total + kGroupInvocations - 1u) / kGroupInvocations;
    const uint k = gl_LocalInvocationIndex, first = min(k * run, total), end = min(first + run, total);
    uint count = 0u;
    for (uint i = first; i < end; ++i) count += tileCodes[markSlot(i)];
    runOffsets[k] = count;
    memoryBarrierShared();
    barrier();
    if (k == 0u) { // exclusive prefix sums of the runs' counts
        uint sum = 0u;
        for (uint j = 0u; j < kGroupInvocations; ++j) {
            const uint c = runOffsets[j];
            runOffsets[j] = sum;
            sum += c;
        }
        tileGroups[0] = sum;
        tileQuadGroups[0] = sum;
    }
    memoryBarrierShared();
    barrier();
    uint slot = runOffsets[k];
    const int columns = tileCount().x;
    for (uint i = first; i < end; ++i)
        if (tileCodes[markSlot(i)] != 0u) tileCodes[slot++] = (i % uint(columns)) | ((i / uint(columns)) << 16);
}

// No return before the barriers, which every invocation of the group must reach.
void main() {
    const ivec2 tile = ivec2(gl_GlobalInvocationID.xy);
    if (all(lessThan(tile, tileCount()))) {
        const uint index = uint(tile.y * tileCount().x + tile.x);
        bool geometry;
        const uvec2 mask = tilePixelMask(tile, geometry);
        if (!geometry && tileScale > 2) geometry = tileHasGeometry(tile);
        tileCodes[markSlot(index)] = geometry ? 1u : 0u;
        const uint maskSlot = pixelMaskSlot(index, tileTotal());
        tileCodes[maskSlot] = mask.x;
        tileCodes[maskSlot + 1u] = mask.y;
    }
    if (finishedLast()) compactMarks();
}
