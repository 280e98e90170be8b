//! variant: SOLID
// Object space to voxel space, in double precision: a scene 1e5 units from the origin keeps
// its sub-voxel precision (the float positions themselves are the only rounding).
#include "../common/common_bindings.h"
#include "voxel_params.glsl"

layout(location = OBSCURA_ATTRIB_POSITION) in vec3 inPosition;
layout(location = VOXEL_LOC_MODEL_TO_VOXEL) uniform dmat4 modelToVoxel;

#ifdef SOLID
out vec3 vVoxel;
#else
out dvec3 vVoxel; // kept in double until the geometry shader makes it triangle-relative
#endif

void main() {
    const dvec3 p = (modelToVoxel * dvec4(dvec3(inPosition), 1.0)).xyz;
#ifdef SOLID
    vVoxel = vec3(p);
    // Orthographic along z: x, y over the R x R grid; depth is clamped, not clipped, so
    // geometry in front of the box still toggles the whole column.
    gl_Position = vec4(vVoxel.xy / vec2(voxel.dims.xy) * 2.0 - 1.0, vVoxel.z / float(voxel.dims.z) * 2.0 - 1.0, 1.0);
#else
    vVoxel = p;
    gl_Position = vec4(0.0, 0.0, 0.0, 1.0); // the geometry shader places the triangle
#endif
}
