// Geometry-aware filters (separable blur at a reduced resolution, joint bilateral
// upsampling): binding points and the parameter block, shared by src/filters/ and
// shaders/filters/. The guide image holds (view normal xyz, view z; z = 0: background) per
// low-resolution pixel, written by the integrator that produced the values.
#ifndef OBSCURA_FILTER_BINDINGS_H
#define OBSCURA_FILTER_BINDINGS_H

#ifdef __cplusplus
#include <glm/glm.hpp>
namespace obscura::shader {
using vec4 = glm::vec4;
using ivec4 = glm::ivec4;
#endif

#define FILTER_PARAMS_UBO_BINDING 3
#define FILTER_GUIDE_UNIT 7
#define FILTER_VALUE_UNIT 8
#define FILTER_DIRECTION_UNIT 9
#define FILTER_VALUE_IMAGE 0
#define FILTER_DIRECTION_IMAGE 1

#define FILTER_LOC_STEP 0 // blur: ivec2 pixel step of this pass

#define FILTER_FLAG_DIRECTION 1 // a second image of unit vectors, renormalized after filtering
#define FILTER_FLAG_UNIT_RANGE 2 // values are clamped to [0, 1]

#define FILTER_WORKGROUP 8

struct FilterParams {
    ivec4 sizes;   // x, y: low resolution; z: scale to the full resolution; w: blur taps each side
    vec4 weights;  // x: depth sigma (relative view depth), y: normal power, z: background value, w: unused
    ivec4 flags;   // x: FILTER_FLAG_*, y, z, w: unused
};

#ifdef __cplusplus
static_assert(sizeof(FilterParams) == 48, "FilterParams must match std140");
} // namespace obscura::shader
#endif

#endif
