// Visibility in voxel space: occupancy, and the first occupied voxel along a segment by
//   (a) jittered ray marching with N steps (the source thesis's method, approximate),
//   (b) exact traversal of every level-0 voxel along the segment (3D DDA),
//   (c) hierarchical traversal that skips empty octree cells (the OR-mipmaps).
// Coordinates are voxel space: [0, R] x [0, R] x [0, D], one unit per voxel.
//
// (b) and (c) visit exactly the same voxels: both run on the same fixed-point segment
// (2^VOXEL_FIXED_SHIFT steps per voxel) and decide every crossing with exact 64-bit integer
// arithmetic. A point on a voxel face belongs to the voxel the segment moves into; several
// faces crossed at the same instant are crossed together (a diagonal step).
#include "int64.glsl"
#include "voxel_params.glsl"
layout(binding = VOXEL_GRID_UNIT) uniform usampler2DArray voxelGrid;
layout(binding = VOXEL_OCTREE_UNIT) uniform usampler2DArray voxelOctree;

const int kVoxelFixedOne = 1 << VOXEL_FIXED_SHIFT;

struct VoxelHit {
    bool hit;
    float t;      // segment parameter in [0, 1] of the entry into the hit voxel (1 when none)
    ivec3 voxel;  // the hit voxel, level 0
    uint fetches; // occupancy tests (texel fetches) made
};

// Grid dimensions at an octree level: x and y halve, the column of slices halves rounding up.
ivec3 voxelDims(int level) {
    return ivec3(voxel.dims.x >> level, voxel.dims.y >> level, (voxel.dims.z + (1 << level) - 1) >> level);
}

bool voxelInside(ivec3 c, int level) {
    return all(greaterThanEqual(c, ivec3(0))) && all(lessThan(c, voxelDims(level)));
}

// Bit z of a 128-slice column stored in one RGBA32UI texel.
// (The word is selected, not indexed with a variable: see voxelNextCrossing.)
bool slicemapBit(uvec4 texel, int z) {
    const int c = (z >> 5) & 3;
    const uint word = c == 0 ? texel.x : (c == 1 ? texel.y : (c == 2 ? texel.z : texel.w));
    return ((word >> uint(z & 31)) & 1u) != 0u;
}

// Level-0 occupancy of a voxel inside the grid.
bool voxelOccupied(ivec3 c) { return slicemapBit(texelFetch(voxelGrid, ivec3(c.xy, c.z >> 7), 0), c.z); }

// Endpoints are accepted within this many voxels of the origin (beyond it float has lost
// the voxel scale anyway, and differences could overflow); others give a miss (or empty space).
const float kVoxelMaxCoordinate = 16777216.0;

bool voxelAcceptedPoint(vec3 p) { return !any(isnan(p)) && all(lessThanEqual(abs(p), vec3(kVoxelMaxCoordinate))); }

// Point occupancy: whether the voxel holding p (voxel coordinates; a point on a face belongs
// to the voxel above it) is set. Points outside the grid, NaN or Inf are empty space.
bool voxelOccupiedAtPoint(vec3 p) {
    if (!voxelAcceptedPoint(p)) return false;
    const ivec3 c = ivec3(floor(p));
    return voxelInside(c, 0) && voxelOccupied(c);
}

// Occupancy of an octree cell: level 0 is the slicemap, level L >= 1 ORs 2^L voxels per axis.
bool voxelOccupiedAt(int level, ivec3 c) {
    if (level == 0) return voxelOccupied(c);
    return slicemapBit(texelFetch(voxelOctree, ivec3(c.xy, c.z >> 7), level - 1), c.z);
}

// ---- the fixed-point segment ------------------------------------------------------------

struct VoxelSegment {
    bool valid;
    ivec3 p0;    // start, fixed point
    ivec3 delta; // end - start, fixed point
    float t0, t1; // the clipped part of the original segment
};

// Clips the segment to the grid and quantizes it. NaN, Inf, beyond the accepted range or no
// overlap with the grid: invalid.
// The part of [0, 1] in which from + t d lies in [0, size] along one axis; empty (lo > hi)
// when a segment parallel to the axis lies outside.
vec2 voxelSlab(float from, float d, float size) {
    if (d == 0.0) return (from < 0.0 || from > size) ? vec2(1.0, 0.0) : vec2(0.0, 1.0);
    const float s0 = -from / d, s1 = (size - from) / d;
    return vec2(min(s0, s1), max(s0, s1));
}

// Clips the segment to the grid and quantizes it. NaN, Inf, beyond the accepted range or no
// overlap with the grid: invalid. (Per-axis work is spelled out, not looped with a variable
// index: see voxelTraceExact.)
VoxelSegment voxelSegment(vec3 from, vec3 to) {
    VoxelSegment s = VoxelSegment(false, ivec3(0), ivec3(0), 0.0, 1.0);
    if (!voxelAcceptedPoint(from) || !voxelAcceptedPoint(to)) return s;
    const vec3 dims = vec3(voxel.dims), d = to - from;
    const vec2 x = voxelSlab(from.x, d.x, dims.x), y = voxelSlab(from.y, d.y, dims.y), z = voxelSlab(from.z, d.z, dims.z);
    const float ta = max(max(0.0, x.x), max(y.x, z.x)), tb = min(min(1.0, x.y), min(y.y, z.y));
    if (ta > tb) return s;
    const ivec3 limit = voxel.dims * kVoxelFixedOne;
    s.p0 = clamp(ivec3(round((from + ta * d) * float(kVoxelFixedOne))), ivec3(0), limit);
    s.delta = clamp(ivec3(round((from + tb * d) * float(kVoxelFixedOne))), ivec3(0), limit) - s.p0;
    s.t0 = ta;
    s.t1 = tb;
    s.valid = true;
    return s;
}

// The voxel holding the start point, on the side the segment moves toward.
int voxelStartCell(int p, int d) {
    return d >= 0 ? (p >> VOXEL_FIXED_SHIFT) : ((p + kVoxelFixedOne - 1) >> VOXEL_FIXED_SHIFT) - 1;
}

ivec3 voxelStartCells(VoxelSegment s) {
    return ivec3(voxelStartCell(s.p0.x, s.delta.x), voxelStartCell(s.p0.y, s.delta.y), voxelStartCell(s.p0.z, s.delta.z));
}

// Time n/den (den > 0) at which an axis with start p and extent delta (fixed point) leaves
// the level-`level` cell with index `cell`.
void voxelCrossing(int p, int delta, int cell, int level, out int n, out int den) {
    const int boundary = ((cell + (delta > 0 ? 1 : 0)) << level) << VOXEL_FIXED_SHIFT;
    n = delta > 0 ? boundary - p : p - boundary;
    den = abs(delta);
}

bool voxelTimeLess(int n1, int d1, int n2, int d2) { return i64Less(i64Mul(n1, d2), i64Mul(n2, d1)); }
bool voxelTimeEqual(int n1, int d1, int n2, int d2) { return i64Equal(i64Mul(n1, d2), i64Mul(n2, d1)); }

// Takes axis `axis` (its bit) into the earliest crossing found so far.
void voxelConsiderAxis(int p, int delta, int cell, int level, int axis, inout bool found, inout int bn, inout int bd,
                       inout int axes) {
    if (delta == 0) return;
    int n, d;
    voxelCrossing(p, delta, cell, level, n, d);
    if (!found || voxelTimeLess(n, d, bn, bd)) {
        bn = n;
        bd = d;
        axes = axis;
        found = true;
    } else if (voxelTimeEqual(n, d, bn, bd)) {
        axes |= axis;
    }
}

// The earliest exit of the level-`level` cell `cells`: its time and the axes that exit then.
// Returns false when the segment ends first (t > 1). The axes are spelled out rather than
// looped over with a variable vector index: Mesa 22.3's llvmpipe gave nondeterministic
// results for such indexing inside the integrators' per-ray loops.
bool voxelNextCrossing(VoxelSegment s, ivec3 cells, int level, out int bn, out int bd, out bvec3 axes) {
    bool found = false;
    bn = 0;
    bd = 1;
    int mask = 0;
    voxelConsiderAxis(s.p0.x, s.delta.x, cells.x, level, 1, found, bn, bd, mask);
    voxelConsiderAxis(s.p0.y, s.delta.y, cells.y, level, 2, found, bn, bd, mask);
    voxelConsiderAxis(s.p0.z, s.delta.z, cells.z, level, 4, found, bn, bd, mask);
    axes = bvec3((mask & 1) != 0, (mask & 2) != 0, (mask & 4) != 0);
    return found && bn <= bd;
}

// The level-0 index along an axis at time n/den, exactly: the largest q with
// q * 2^S * den <= p0 * den + n * delta (moving +, or not moving), or < (moving -).
// Whether the point x / den (fixed point, scaled by den) is in voxel q or above it, with a
// point on a face belonging to the voxel the segment moves into.
bool voxelAtOrAbove(I64 x, int q, int delta, int den) {
    const I64 face = i64Mul(q << VOXEL_FIXED_SHIFT, den);
    return delta > 0 ? i64LessEqual(face, x) : i64Less(face, x);
}

int voxelCellAt(int p0, int delta, int n, int den) {
    const I64 x = i64Add(i64Mul(p0, den), i64Mul(n, delta));
    int q = int(floor((float(p0) + float(n) / float(den) * float(delta)) / float(kVoxelFixedOne)));
    // The float estimate is off by at most one; two corrections each way, unrolled (loops
    // with a break here were miscompiled by llvmpipe inside the integrators' ray loops).
    q += voxelAtOrAbove(x, q + 1, delta, den) ? 1 : 0;
    q += voxelAtOrAbove(x, q + 1, delta, den) ? 1 : 0;
    q -= voxelAtOrAbove(x, q, delta, den) ? 0 : 1;
    q -= voxelAtOrAbove(x, q, delta, den) ? 0 : 1;
    return q;
}

// The level-0 index along one axis after a crossing at time bn/bd: the first voxel of the
// next cell on a crossing axis, the exact index at that time on a moving one, unchanged on
// a still one.
int voxelCellAfter(bool crossed, int p, int delta, int cell, int level, int bn, int bd, int current) {
    if (crossed) return delta > 0 ? (cell + 1) << level : (cell << level) - 1;
    return delta != 0 ? voxelCellAt(p, delta, bn, bd) : current;
}

VoxelHit voxelMiss() { return VoxelHit(false, 1.0, ivec3(-1), 0u); }

float voxelHitParameter(VoxelSegment s, int tn, int td) { return s.t0 + float(tn) / float(td) * (s.t1 - s.t0); }

// (b) Every level-0 voxel along the segment, in order.
// The traversals leave their loops with `break` and return once, at the end: returning
// from inside a loop of a function that is itself called in a loop (as the integrators do,
// once per ray) was miscompiled by Mesa 22.3's llvmpipe into nondeterministic results.
VoxelHit voxelTraceExact(vec3 from, vec3 to) {
    VoxelHit r = voxelMiss();
    const VoxelSegment s = voxelSegment(from, to);
    ivec3 c = voxelStartCells(s);
    int tn = 0, td = 1;
    const ivec3 dims = voxelDims(0);
    const int maxSteps = s.valid ? dims.x + dims.y + dims.z + 3 : 0;
    for (int step = 0; step < maxSteps; ++step) {
        if (!voxelInside(c, 0)) break;
        ++r.fetches;
        if (voxelOccupied(c)) {
            r.hit = true;
            r.voxel = c;
            r.t = voxelHitParameter(s, tn, td);
            break;
        }
        int bn, bd;
        bvec3 axes;
        if (!voxelNextCrossing(s, c, 0, bn, bd, axes)) break;
        c += ivec3(axes) * sign(s.delta);
        tn = bn;
        td = bd;
    }
    return r;
}

// (c) The same voxels, skipping empty octree cells: ascend after leaving an empty cell,
// descend into occupied ones.
VoxelHit voxelTraceHierarchical(vec3 from, vec3 to) {
    VoxelHit r = voxelMiss();
    const VoxelSegment s = voxelSegment(from, to);
    ivec3 c = voxelStartCells(s);
    int tn = 0, td = 1;
    const int top = voxel.octreeLevels;
    int level = top;
    const ivec3 dims = voxelDims(0);
    const int maxSteps = s.valid ? 2 * (top + 2) * (dims.x + dims.y + dims.z + 3) : 0;
    for (int step = 0; step < maxSteps; ++step) {
        const ivec3 cell = c >> level;
        if (!voxelInside(cell, level)) break;
        ++r.fetches;
        const bool occupied = voxelOccupiedAt(level, cell);
        if (occupied && level == 0) {
            r.hit = true;
            r.voxel = c;
            r.t = voxelHitParameter(s, tn, td);
            break;
        }
        if (occupied) {
            --level; // descend into the occupied cell
        } else {
            int bn, bd;
            bvec3 axes;
            if (!voxelNextCrossing(s, cell, level, bn, bd, axes)) break;
            c = ivec3(voxelCellAfter(axes.x, s.p0.x, s.delta.x, cell.x, level, bn, bd, c.x),
                      voxelCellAfter(axes.y, s.p0.y, s.delta.y, cell.y, level, bn, bd, c.y),
                      voxelCellAfter(axes.z, s.p0.z, s.delta.z, cell.z, level, bn, bd, c.z));
            tn = bn;
            td = bd;
            level = min(level + 1, top);
        }
    }
    return r;
}

// (a) `steps` occupancy samples at t = (i + jitter) / steps, jitter in [0, 1).
VoxelHit voxelTraceMarch(vec3 from, vec3 to, int steps, float jitter) {
    VoxelHit r = voxelMiss();
    if (!voxelAcceptedPoint(from) || !voxelAcceptedPoint(to)) return r;
    for (int i = 0; i < steps; ++i) {
        const float t = (float(i) + jitter) / float(steps);
        const vec3 p = mix(from, to, t);
        // Clamped before the conversion: a float far outside int range has no defined int.
        const ivec3 c = ivec3(floor(clamp(p, vec3(-1.0), vec3(voxel.dims) + 1.0)));
        if (!voxelInside(c, 0)) continue;
        ++r.fetches;
        if (voxelOccupied(c)) {
            r.hit = true;
            r.voxel = c;
            r.t = t;
            return r;
        }
    }
    return r;
}
