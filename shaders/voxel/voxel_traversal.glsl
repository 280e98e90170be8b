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
bool slicemapBit(uvec4 texel, int z) { return ((texel[(z >> 5) & 3] >> uint(z & 31)) & 1u) != 0u; }

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
VoxelSegment voxelSegment(vec3 from, vec3 to) {
    VoxelSegment s = VoxelSegment(false, ivec3(0), ivec3(0), 0.0, 1.0);
    if (!voxelAcceptedPoint(from) || !voxelAcceptedPoint(to)) return s;
    const vec3 dims = vec3(voxel.dims.xyz), d = to - from;
    float ta = 0.0, tb = 1.0;
    for (int a = 0; a < 3; ++a) {
        if (d[a] == 0.0) {
            if (from[a] < 0.0 || from[a] > dims[a]) return s;
            continue;
        }
        float s0 = -from[a] / d[a], s1 = (dims[a] - from[a]) / d[a];
        ta = max(ta, min(s0, s1));
        tb = min(tb, max(s0, s1));
    }
    if (ta > tb) return s;
    const ivec3 limit = voxel.dims.xyz * kVoxelFixedOne;
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

// Time n/den (den > 0) at which axis a leaves the level-`level` cell with index `cell`.
void voxelCrossing(VoxelSegment s, int a, int cell, int level, out int n, out int den) {
    const int boundary = ((cell + (s.delta[a] > 0 ? 1 : 0)) << level) << VOXEL_FIXED_SHIFT;
    n = s.delta[a] > 0 ? boundary - s.p0[a] : s.p0[a] - boundary;
    den = abs(s.delta[a]);
}

bool voxelTimeLess(int n1, int d1, int n2, int d2) { return i64Less(i64Mul(n1, d2), i64Mul(n2, d1)); }
bool voxelTimeEqual(int n1, int d1, int n2, int d2) { return i64Equal(i64Mul(n1, d2), i64Mul(n2, d1)); }

// The earliest exit of the level-`level` cell `cells`: its time and the axes that exit then.
// Returns false when the segment ends first (t > 1).
bool voxelNextCrossing(VoxelSegment s, ivec3 cells, int level, out int bn, out int bd, out bvec3 axes) {
    bool any = false;
    bn = 0;
    bd = 1;
    axes = bvec3(false);
    for (int a = 0; a < 3; ++a) {
        if (s.delta[a] == 0) continue;
        int n, d;
        voxelCrossing(s, a, cells[a], level, n, d);
        if (!any || voxelTimeLess(n, d, bn, bd)) {
            bn = n;
            bd = d;
            axes = bvec3(false);
            axes[a] = true;
            any = true;
        } else if (voxelTimeEqual(n, d, bn, bd)) {
            axes[a] = true;
        }
    }
    return any && bn <= bd;
}

// The level-0 index along an axis at time n/den, exactly: the largest q with
// q * 2^S * den <= p0 * den + n * delta (moving +, or not moving), or < (moving -).
int voxelCellAt(int p0, int delta, int n, int den) {
    const I64 x = i64Add(i64Mul(p0, den), i64Mul(n, delta));
    int q = int(floor((float(p0) + float(n) / float(den) * float(delta)) / float(kVoxelFixedOne)));
    for (int i = 0; i < 4; ++i) { // the float estimate is off by at most one
        const I64 next = i64Mul((q + 1) << VOXEL_FIXED_SHIFT, den);
        if (delta > 0 ? i64LessEqual(next, x) : i64Less(next, x)) ++q;
        else break;
    }
    for (int i = 0; i < 4; ++i) {
        const I64 here = i64Mul(q << VOXEL_FIXED_SHIFT, den);
        if (delta > 0 ? i64Less(x, here) : i64LessEqual(x, here)) --q;
        else break;
    }
    return q;
}

VoxelHit voxelMiss() { return VoxelHit(false, 1.0, ivec3(-1), 0u); }

float voxelHitParameter(VoxelSegment s, int tn, int td) { return s.t0 + float(tn) / float(td) * (s.t1 - s.t0); }

// (b) Every level-0 voxel along the segment, in order.
VoxelHit voxelTraceExact(vec3 from, vec3 to) {
    VoxelHit r = voxelMiss();
    const VoxelSegment s = voxelSegment(from, to);
    if (!s.valid) return r;
    ivec3 c = voxelStartCells(s);
    int tn = 0, td = 1;
    const ivec3 dims = voxelDims(0);
    for (int step = 0; step < dims.x + dims.y + dims.z + 3; ++step) {
        if (!voxelInside(c, 0)) return r;
        ++r.fetches;
        if (voxelOccupied(c)) {
            r.hit = true;
            r.voxel = c;
            r.t = voxelHitParameter(s, tn, td);
            return r;
        }
        int bn, bd;
        bvec3 axes;
        if (!voxelNextCrossing(s, c, 0, bn, bd, axes)) return r;
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
    if (!s.valid) return r;
    ivec3 c = voxelStartCells(s);
    int tn = 0, td = 1;
    const int top = voxel.dims.w;
    int level = top;
    const ivec3 dims = voxelDims(0);
    for (int step = 0; step < 2 * (top + 2) * (dims.x + dims.y + dims.z + 3); ++step) {
        const ivec3 cell = c >> level;
        if (!voxelInside(cell, level)) return r;
        ++r.fetches;
        if (voxelOccupiedAt(level, cell)) {
            if (level == 0) {
                r.hit = true;
                r.voxel = c;
                r.t = voxelHitParameter(s, tn, td);
                return r;
            }
            --level;
            continue;
        }
        int bn, bd;
        bvec3 axes;
        if (!voxelNextCrossing(s, cell, level, bn, bd, axes)) return r;
        for (int a = 0; a < 3; ++a) {
            if (axes[a]) c[a] = s.delta[a] > 0 ? (cell[a] + 1) << level : (cell[a] << level) - 1;
            else if (s.delta[a] != 0) c[a] = voxelCellAt(s.p0[a], s.delta[a], bn, bd);
        }
        tn = bn;
        td = bd;
        level = min(level + 1, top);
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
        const ivec3 c = ivec3(floor(clamp(p, vec3(-1.0), vec3(voxel.dims.xyz) + 1.0)));
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
