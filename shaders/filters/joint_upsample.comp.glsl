// Joint bilateral upsampling to the G-buffer's resolution: the four low-resolution pixels
// around each G-buffer pixel, weighted bilinearly and by guideWeight against the pixel's own
// view depth and normal. Where no neighbour is similar, the one nearest in depth is taken
// (for directions, its offset from its normal, see directionOffset).
// Background pixels get the background value (and no direction); with a background z
// (GuidedFilterSettings::backgroundZ) they blend at that depth like the others, and the
// normals are not read (any texture may stand at VIS_NORMAL_UNIT). MODULATE: each written
// pixel's value times its own texel of the factor (filter_common.glsl). REFINE: pixels whose
// similar neighbours carry less than the threshold's share of the bilinear weight are listed
// for the integrator to compute instead (refine_list.glsl); they are written here too, so
// that they hold the blended value when the list overflows and nothing is refined.
//
// One invocation writes a 2 x 2 quad of G-buffer pixels. With an even scale the quad's four
// pixels share the same four low-resolution neighbours, so they are loaded once per quad,
// and the quad's own depth and normal are one textureGather per channel. TILES: only the
// quads of the tiles with geometry (geometry_tiles.glsl); the caller has cleared the images to
// what background pixels get. HALF (scale 2): the quad's first pixel lies on its lower
// neighbour and the others halfway between neighbours, so 7 of the 16 pixel-neighbour pairs
// have bilinear weight 0 and add exactly 0; their guide weights are not computed (main).
//! variant: RGB
//! variant: DIRECTION
//! variant: REFINE
//! variant: DIRECTION REFINE
//! variant: RGB REFINE
//! variant: RGB MODULATE
//! variant: RGB REFINE MODULATE
//! variant: DIRECTION REFINE TILES
//! variant: RGB REFINE MODULATE TILES
//! variant: TILES
//! variant: HALF
//! variant: RGB HALF
//! variant: DIRECTION REFINE TILES HALF
//! variant: RGB REFINE MODULATE TILES HALF
#include "../visibility/screen_march.glsl"
#include "filter_common.glsl"
#include "geometry_tiles.glsl"
#ifdef REFINE
#include "refine_list.glsl"
#endif

layout(local_size_x = FILTER_WORKGROUP, local_size_y = FILTER_WORKGROUP) in;

// The running weighted sums for one G-buffer pixel (of the values' offsets from the quad's
// first usable neighbour's, see weightedMean; of the directions' offsets from their normals,
// see directionOffset), and the neighbour nearest in depth.
struct Blend {
    FILTER_VALUE offsets, nearest;
    vec3 direction, nearestDirection;
    float total, nearestDz;
};

// One G-buffer pixel: its view normal and z, and where it lies between the neighbours.
struct Target {
    vec3 n;
    float z;
    vec2 f;
    bool background;
};

Target makeTarget(float depth, vec4 normalTexel, vec2 f) {
    // A background z: background pixels blend at it; the normals are unread.
    if (filterParams.backgroundZ != 0.0) {
        const float z = isBackground(depth) ? filterParams.backgroundZ : viewZFromDepth(depth);
        return Target(vec3(0.0, 0.0, 1.0), z, f, false);
    }
    const bool background = isBackground(depth) || normalTexel.a == 0.0;
    return Target(normalTexel.xyz, background ? 1.0 : viewZFromDepth(depth), f, background);
}

Blend startBlend() { return Blend(FILTER_VALUE(0.0), FILTER_VALUE(filterParams.background), vec3(0.0), vec3(0.0), 0.0, 1e30); }

// One low-resolution neighbour: its guide (w = 0: background), value and direction offset.
struct Neighbour {
    vec4 guide;
    FILTER_VALUE value;
    vec3 direction;
};

// Neighbour `corner` (0 or 1 per axis) of the low-resolution pixel `base`. Past the last row
// or column the last one repeats (the image's own edge).
Neighbour loadNeighbour(ivec2 base, ivec2 corner) {
    const ivec2 q = min(base + corner, filterLowSize() - 1);
    const vec4 guide = imageLoad(guideIn, q);
#ifdef DIRECTION
    return Neighbour(guide, loadValue(q), directionOffset(q, guide.xyz));
#else
    return Neighbour(guide, loadValue(q), vec3(0.0));
#endif
}

// How much neighbour `corner` counts for target t: bilinearly and by guideWeight.
float neighbourWeight(Target t, ivec2 corner, Neighbour q) {
    const vec2 bilinear = mix(1.0 - t.f, t.f, vec2(corner));
    return q.guide.w != 0.0 ? bilinear.x * bilinear.y * guideWeight(t.n, t.z, q.guide.xyz, q.guide.w) : 0.0;
}

void addWeighted(inout Blend b, float w, Neighbour q, FILTER_VALUE anchor) {
    b.offsets += w * (q.value - anchor);
    b.direction += w * q.direction;
    b.total += w;
}

// Keeps the neighbour nearest in depth among the usable ones (the fallback, see writePixel).
void trackNearest(inout Blend b, Target t, Neighbour q) {
    const float dz = abs(q.guide.w - t.z);
    if (q.guide.w != 0.0 && dz < b.nearestDz) {
        b.nearestDz = dz;
        b.nearest = q.value;
        b.nearestDirection = q.direction;
    }
}

// Takes q's value as the anchor the blends' offsets are measured from (see Blend) if it is the
// first usable neighbour.
void anchorOnFirstUsable(Neighbour q, inout FILTER_VALUE anchor, inout bool anchored) {
    if (!anchored && q.guide.w != 0.0) {
        anchor = q.value;
        anchored = true;
    }
}

// Adds neighbour `corner` to a blend.
void accumulate(inout Blend b, Target t, ivec2 corner, Neighbour q, FILTER_VALUE anchor) {
    addWeighted(b, neighbourWeight(t, corner, q), q, anchor);
    trackNearest(b, t, q);
}

// Whether the pixel is in the image (odd sizes: the quad's far half is outside) and, with
// REFINE, has too little similar-neighbour weight, so that the integrator computes it.
bool inImage(ivec2 pixel) { return all(lessThan(pixel, frameSize())); }
bool wantsRefinement(ivec2 pixel, Target t, Blend b) { return inImage(pixel) && !t.background && b.total < filterParams.refineThreshold; }

// Single exit: Mesa 22.3 llvmpipe miscompiles early returns in inlined code (see
// voxel_traversal.glsl).
void writePixel(ivec2 pixel, Target t, Blend b, FILTER_VALUE anchor) {
    const bool weighted = b.total > 1e-6;
    const FILTER_VALUE blended = filterFinish(modulated(pixel, weighted ? weightedMean(anchor, b.offsets, b.total) : b.nearest));
    const bool inside = inImage(pixel);
    if (inside) imageStore(valueOut, pixel, vec4(t.background ? FILTER_VALUE(filterParams.background) : blended));
#ifdef DIRECTION
    if (inside) {
        const vec3 direction = directionFromOffset(t.n, weighted ? b.direction / b.total : b.nearestDirection);
        imageStore(directionOut, pixel, t.background ? vec4(0.0) : vec4(direction, 1.0));
    }
#endif
}

// textureGather returns the 2 x 2 texels around its point in the order x: (0, 1),
// y: (1, 1), z: (1, 0), w: (0, 0) from the lower corner. The point between texel `corner` and
// `corner` + (1, 1) selects exactly them; the clamp-to-edge sampler repeats the last row and
// column past the image (odd sizes), where the quad's far half is not written.
vec2 gatherPoint(ivec2 corner, ivec2 size) { return (vec2(corner) + 1.0) / vec2(size); }

void main() {
    const int s = filterScale(); // 2 or 4: even, so the whole quad has the same lower neighbour
#ifdef TILES
    const ivec2 p00 = 2 * tiledQuad(s);
#else
    const ivec2 p00 = 2 * ivec2(gl_GlobalInvocationID.xy);
#endif
    if (any(greaterThanEqual(p00, frameSize()))) return;
    const ivec2 base = p00 / s;
    // Low-resolution pixel i covers G-buffer pixels [i s, i s + s) and was computed at i s.
    const vec2 f00 = vec2(p00 - base * s) / float(s), step = vec2(1.0 / float(s));
    const vec2 fullUv = gatherPoint(p00, frameSize());
    const vec4 depth = textureGather(visDepth, fullUv, 0);
    const vec4 nx = textureGather(visNormal, fullUv, 0), ny = textureGather(visNormal, fullUv, 1);
    const vec4 nz = textureGather(visNormal, fullUv, 2), na = textureGather(visNormal, fullUv, 3);
    const Target t00 = makeTarget(depth.w, vec4(nx.w, ny.w, nz.w, na.w), f00);
    const Target t10 = makeTarget(depth.z, vec4(nx.z, ny.z, nz.z, na.z), f00 + vec2(step.x, 0.0));
    const Target t01 = makeTarget(depth.x, vec4(nx.x, ny.x, nz.x, na.x), f00 + vec2(0.0, step.y));
    const Target t11 = makeTarget(depth.y, vec4(nx.y, ny.y, nz.y, na.y), f00 + step);
    Blend b00 = startBlend(), b10 = startBlend(), b01 = startBlend(), b11 = startBlend();
    // Loops, not straight code, so that on llvmpipe a SIMD batch of background quads skips
    // most neighbours' loads: straight-line code runs for masked-off lanes too, and so does a
    // loop's first pass, but later passes stop once no lane is left (benchmarks/README.md).
    const bool geometry = !(t00.background && t10.background && t01.background && t11.background);
    FILTER_VALUE anchor = FILTER_VALUE(0.0);
    bool anchored = false;
#ifdef HALF
    // Neighbour (0, 0) counts for all four pixels, (1, 0) for the right two, (0, 1) for the
    // top two, (1, 1) for the last one; every pixel still looks for its nearest among all four.
    // The same sums in the same order as accumulate's, less the terms of bilinear weight 0:
    // 10 guide weights a quad instead of 16. On llvmpipe at 512 x 512 that took the pass to
    // 0.85-0.95 of its time (benchmarks/README.md): an `if` would not, as masked lanes run it.
    const Neighbour q0 = loadNeighbour(base, ivec2(0));
    anchorOnFirstUsable(q0, anchor, anchored);
    accumulate(b00, t00, ivec2(0), q0, anchor);
    accumulate(b10, t10, ivec2(0), q0, anchor);
    accumulate(b01, t01, ivec2(0), q0, anchor);
    accumulate(b11, t11, ivec2(0), q0, anchor);
    for (int i = 1; i < (geometry ? 4 : 0); ++i) {
        const ivec2 corner = ivec2(i & 1, i >> 1);
        const Neighbour q = loadNeighbour(base, corner);
        anchorOnFirstUsable(q, anchor, anchored);
        // The one other pixel it counts for: (1, 0) and (0, 1) their own side's; for (1, 1)
        // none, so its weight is 0 (t10 lies on the lower row, bilinear y 0) and adds 0.
        const bool right = corner.x == 1;
        const float w = neighbourWeight(right ? t10 : t01, corner, q);
        if (right) addWeighted(b10, w, q, anchor);
        else addWeighted(b01, w, q, anchor);
        trackNearest(b00, t00, q);
        trackNearest(b10, t10, q);
        trackNearest(b01, t01, q);
        accumulate(b11, t11, corner, q, anchor);
    }
#else
    for (int i = 0; i < (geometry ? 4 : 0); ++i) {
        const ivec2 corner = ivec2(i & 1, i >> 1);
        const Neighbour q = loadNeighbour(base, corner);
        anchorOnFirstUsable(q, anchor, anchored);
        accumulate(b00, t00, corner, q, anchor);
        accumulate(b10, t10, corner, q, anchor);
        accumulate(b01, t01, corner, q, anchor);
        accumulate(b11, t11, corner, q, anchor);
    }
#endif
#ifdef REFINE
    refineAppendQuad(p00, bvec4(wantsRefinement(p00, t00, b00), wantsRefinement(p00 + ivec2(1, 0), t10, b10),
                                wantsRefinement(p00 + ivec2(0, 1), t01, b01), wantsRefinement(p00 + ivec2(1, 1), t11, b11)));
#endif
    writePixel(p00, t00, b00, anchor);
    writePixel(p00 + ivec2(1, 0), t10, b10, anchor);
    writePixel(p00 + ivec2(0, 1), t01, b01, anchor);
    writePixel(p00 + ivec2(1, 1), t11, b11, anchor);
}
