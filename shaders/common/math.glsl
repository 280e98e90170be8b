// Small numerically guarded helpers.
#ifndef OBSCURA_PI
#define OBSCURA_PI 3.14159265358979323846
#endif

// Largest finite half float: radiance written to RGBA16F targets is clamped to it, so a
// very bright value saturates instead of turning into Inf.
const float kHalfMax = 65504.0;
const float kFloatMax = 3.402823466e38;
const float kLog2E = 1.44269504088896341; // log2(e): exp(x) = exp2(x kLog2E)

bool allFinite(vec3 v) { return !any(isnan(v)) && !any(isinf(v)); }

// Whether a pixel's stored depth stands for no surface: the clear depth, a value no
// rasterizer writes, or one beyond `farthestDepth` (DepthReconstruction::farthestDepth, the
// depth of kMaxViewDistance; below it with reversed-Z, whose clear depth is 0, above it
// otherwise). A host's float depth texture may hold anything (ARB_depth_buffer_float stores
// values outside [0, 1] unclamped): NaN, +-Inf, negative or above 1 is background.
// Subnormals and -0.0 count as 0, as GPUs that flush denormals read them. Tested on the
// bits: GLSL 4.50 (4.7.1) does not require NaNs to be implemented, so a comparison or isnan
// need not see one. Floats in (0, 1] are the patterns up to 0x3F800000; the normal ones start
// at 0x00800000.
bool isBackgroundDepth(float depth, float clearDepth, float farthestDepth) {
    const uint bits = floatBitsToUint(depth);
    const bool zero = (bits & 0x7FFFFFFFu) < 0x00800000u;
    if (!zero && bits > 0x3F800000u) return true;
    const float d = zero ? 0.0 : depth;
    return d == clearDepth || (clearDepth == 0.0 ? d < farthestDepth : d > farthestDepth);
}

// Normalizes v; returns `fallback` for zero, NaN or Inf input. Scaling by the largest
// component first avoids overflow and underflow in dot(v, v).
vec3 safeNormalize(vec3 v, vec3 fallback) {
    if (!allFinite(v)) return fallback;
    float m = max(max(abs(v.x), abs(v.y)), abs(v.z));
    if (!(m > 0.0)) return fallback;
    v /= m;
    return v * inversesqrt(dot(v, v));
}

// |v| for any finite v. length() squares the components, and a square overflows float past
// about 1.8e19: a screen-space march out to a radius that long (the radius's range is
// (0, inf)) measured its samples as infinitely far, and their rounding tolerance made nothing
// hidden. Vectors with a component from 2^60 on are scaled by it first; shorter ones take
// length() as they are, so their results keep every bit. An infinite component gives Inf, as
// length() does.
float lengthWithoutOverflow(vec3 v) {
    const float m = max(max(abs(v.x), abs(v.y)), abs(v.z));
    if (m < 1.152921504606847e18) return length(v);
    return isinf(m) ? m : m * length(v / m);
}

// v rounded to the nearest half float (ties away from zero), so that storing it into a
// 16-bit float image is exact: GL leaves that conversion's rounding to the implementation,
// and llvmpipe's rounds toward zero, which turns 0.99999994 into 0.99951 (a float's last bit
// of error, an unoccluded AO, became a whole half ulp). For finite |v| < 65520 (callers clamp
// to kHalfMax; 65520 and up round to Inf, as they would to nearest); below half's normal
// range (2^-14) the store may still round, by less than 2^-24.
float roundedToHalf(float v) { return uintBitsToFloat((floatBitsToUint(v) + 0x1000u) & 0xFFFFE000u); }
vec4 roundedToHalf(vec4 v) { return uintBitsToFloat((floatBitsToUint(v) + uvec4(0x1000u)) & uvec4(0xFFFFE000u)); }

// NaN becomes 0 (min/max do not define what they return for NaN).
vec3 clampRadiance(vec3 radiance) {
    radiance = mix(radiance, vec3(0.0), isnan(radiance));
    return clamp(radiance, vec3(0.0), vec3(kHalfMax));
}

// A reflectance as the shaders use it: in [0, 1], NaN as 0. A host's float albedo may hold
// anything (HostGBuffer::albedo), and its product with radiance must stay finite.
vec3 clampAlbedo(vec3 albedo) { return clamp(mix(albedo, vec3(0.0), isnan(albedo)), vec3(0.0), vec3(1.0)); }

// A spot light's cone (the reference's spotCone, src/reference/estimators.hpp): smooth from
// cos(outer) to cos(inner); a hard edge when they coincide (smoothstep is undefined for equal
// edges).
float spotCone(float c, float cosInner, float cosOuter) {
    float width = cosInner - cosOuter;
    if (!(width > 0.0)) return c >= cosOuter ? 1.0 : 0.0;
    float t = clamp((c - cosOuter) / width, 0.0, 1.0);
    return t * t * (3.0 - 2.0 * t);
}
