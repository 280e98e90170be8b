// Exact 64-bit integer products and comparisons from 32-bit integers (core GLSL 4.00:
// imulExtended, uaddCarry), for the exact voxel traversal.
struct I64 {
    int hi;
    uint lo;
};

I64 i64Mul(int a, int b) {
    int hi, lo;
    imulExtended(a, b, hi, lo);
    return I64(hi, uint(lo));
}

I64 i64Add(I64 a, I64 b) {
    uint carry;
    uint lo = uaddCarry(a.lo, b.lo, carry);
    return I64(a.hi + b.hi + int(carry), lo);
}

bool i64Less(I64 a, I64 b) { return a.hi < b.hi || (a.hi == b.hi && a.lo < b.lo); }
bool i64LessEqual(I64 a, I64 b) { return a.hi < b.hi || (a.hi == b.hi && a.lo <= b.lo); }
bool i64Equal(I64 a, I64 b) { return a.hi == b.hi && a.lo == b.lo; }
