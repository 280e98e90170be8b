// What the blur and the upsampling share: the parameter block, the low-resolution images and
// the guide weights. RGB: the value is rgba16f (else r16f); DIRECTION: a second image of unit
// vectors (bent normals) filtered with the same weights as offsets from their normals
// (directionOffset); MODULATE (with RGB): the last step multiplies each G-buffer pixel's rgb
// by its own texel of a G-buffer-sized texture (indirect light's albedo, see modulated).
#include "../common/math.glsl"
#include "filter_bindings.h"

#ifdef RGB
#define FILTER_VALUE vec4
#define FILTER_FORMAT rgba16f
#define FILTER_VALUE_OF(texel) (texel)
#else
#define FILTER_VALUE float
#define FILTER_FORMAT r16f
#define FILTER_VALUE_OF(texel) (texel).r
#endif

layout(std140, binding = FILTER_PARAMS_UBO_BINDING) uniform FilterBlock {
    FilterParams filterParams;
};

layout(binding = FILTER_GUIDE_IN_IMAGE, rgba32f) readonly uniform image2D guideIn;
layout(binding = FILTER_VALUE_IN_IMAGE, FILTER_FORMAT) readonly uniform image2D valueIn;
layout(binding = FILTER_VALUE_IMAGE, FILTER_FORMAT) writeonly uniform image2D valueOut;
#ifdef DIRECTION
layout(binding = FILTER_DIRECTION_IN_IMAGE, rgba16f) readonly uniform image2D directionIn;
layout(binding = FILTER_DIRECTION_IMAGE, rgba16f) writeonly uniform image2D directionOut;
#endif

ivec2 filterLowSize() { return filterParams.lowSize; }
int filterScale() { return filterParams.scale; }

bool insideLow(ivec2 q) { return all(greaterThanEqual(q, ivec2(0))) && all(lessThan(q, filterLowSize())); }

FILTER_VALUE loadValue(ivec2 q) { return FILTER_VALUE_OF(imageLoad(valueIn, q)); }

#ifdef MODULATE
layout(binding = FILTER_MODULATE_UNIT) uniform sampler2D filterModulate;

// A filtered value times the factor at G-buffer pixel `pixel`. Indirect light is filtered
// without its albedo, whose texture edges the guide does not see, and gets each pixel's own
// albedo here: after the blur at full resolution, in the upsampling otherwise.
// The min: the upsampling's quads of odd sizes reach a column or row past the image, which
// they do not write.
FILTER_VALUE modulated(ivec2 pixel, FILTER_VALUE v) {
    const ivec2 texel = min(pixel, textureSize(filterModulate, 0) - 1);
    return vec4(v.rgb * clampAlbedo(texelFetch(filterModulate, texel, 0).rgb), v.a);
}
#else
FILTER_VALUE modulated(ivec2 pixel, FILTER_VALUE v) { return v; }
#endif

#ifdef DIRECTION
// Directions are filtered as their offsets from the normal of the pixel they belong to, and
// the mean offset is added to the normal of the pixel written. On a curved surface the
// neighbours' bent normals differ by the turn of their own normals, which a mean of the
// directions themselves carries into the result: duck at 128x128, ao.voxel high_half, bent
// normal RMSE 0.044 that way against 0.015 at full resolution.
vec3 directionOffset(ivec2 q, vec3 normal) { return imageLoad(directionIn, q).xyz - normal; }
vec3 directionFromOffset(vec3 normal, vec3 meanOffset) { return safeNormalize(normal + meanOffset, normal); }
#endif

// A weighted mean as `anchor` plus the weighted offsets from it over their total weight. A
// plain sum / total of equal values can come out below them: GLSL 4.50 (4.7.1) allows
// division 2.5 ULP of error, and float-to-half stores may round toward zero (llvmpipe's do),
// which turns 0.99999994 into 0.99951. Offsets from a value the mean contains are exactly 0
// for a constant image, so it stays exactly constant (an open plane's AO stays 1).
FILTER_VALUE weightedMean(FILTER_VALUE anchor, FILTER_VALUE offsets, float total) { return anchor + offsets / total; }

// A value as stored: clamped to [0, 1] when it is a fraction, else to [0, kHalfMax] (radiance:
// a weighted mean of values near kHalfMax and near 0 can round a hair below 0, -4.4e-4 seen
// on a host's radiance poisoned with such values), rounded to the nearest half float (see
// roundedToHalf).
FILTER_VALUE filterFinish(FILTER_VALUE v) {
    const float hi = (filterParams.flags & FILTER_FLAG_UNIT_RANGE) != 0 ? 1.0 : kHalfMax;
    return roundedToHalf(clamp(v, FILTER_VALUE(0.0), FILTER_VALUE(hi)));
}

// log2 of how much a sample with view normal n2 and view z z2 counts for a pixel with n1, z1:
// a Gaussian in the relative depth difference times max(0, n1.n2)^power. As one exponent, so
// that a tap costs one exp2 (the blur adds its spatial Gaussian to it) instead of two
// exponentials and a pow: on llvmpipe that took an eighth off the blur. Power 0 is weight 1
// (pow(0, 0) is undefined in GLSL); a normal 90 degrees or more away gets 2^-200, which is 0
// in float. Equal depths count as no difference even where sigma |z1| is 0 (the product of a
// subnormal sigma and a small z underflows, or a GPU flushes the sigma), which would make
// 0/0; any other difference over 0 is infinite and weighs 0.
float guideLog2Weight(vec3 n1, float z1, vec3 n2, float z2) {
    const float difference = z2 - z1;
    const float dz = difference == 0.0 ? 0.0 : difference / (filterParams.depthSigma * abs(z1));
    const float p = filterParams.normalPower, c = dot(n1, n2);
    const float normalTerm = p > 0.0 ? (c > 0.0 ? p * log2(c) : -200.0) : 0.0;
    return -0.5 * kLog2E * dz * dz + normalTerm;
}

float guideWeight(vec3 n1, float z1, vec3 n2, float z2) { return exp2(guideLog2Weight(n1, z1, n2, z2)); }
