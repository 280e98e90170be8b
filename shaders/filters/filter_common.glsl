// What the blur and the upsampling share: the parameter block and the guide weights.
#include "../common/math.glsl"
#include "filter_bindings.h"

#ifdef RGB
#define FILTER_VALUE vec4
#define FILTER_FORMAT rgba16f
#define FILTER_FETCH(t, q) texelFetch(t, q, 0)
#else
#define FILTER_VALUE float
#define FILTER_FORMAT r16f
#define FILTER_FETCH(t, q) texelFetch(t, q, 0).r
#endif

layout(std140, binding = FILTER_PARAMS_UBO_BINDING) uniform FilterBlock {
    FilterParams filterParams;
};

ivec2 filterLowSize() { return filterParams.sizes.xy; }
int filterScale() { return filterParams.sizes.z; }
bool filterHasDirection() { return (filterParams.flags.x & FILTER_FLAG_DIRECTION) != 0; }

FILTER_VALUE filterFinish(FILTER_VALUE v) {
    if ((filterParams.flags.x & FILTER_FLAG_UNIT_RANGE) != 0) return clamp(v, FILTER_VALUE(0.0), FILTER_VALUE(1.0));
    return v;
}

// How much a sample with view normal n2 and view z z2 counts for a pixel with n1, z1:
// Gaussian in the relative depth difference times max(0, n1.n2)^power (1 for power 0:
// pow(0, 0) is undefined in GLSL).
float guideWeight(vec3 n1, float z1, vec3 n2, float z2) {
    const float dz = (z2 - z1) / (filterParams.weights.x * abs(z1));
    const float p = filterParams.weights.y;
    return exp(-0.5 * dz * dz) * (p > 0.0 ? pow(max(dot(n1, n2), 0.0), p) : 1.0);
}
