// Per-pixel depth of a paraboloid map: the distance along this texel's exact direction to
// the triangle's plane, not the depth interpolated between the projected corners (which
// is wrong inside the triangle, since the projection is not linear).
#include "shadow_bindings.h"

// x, y: window depth = y / distance - x; z: 2 / resolution (one texel in map coordinates)
layout(location = SHADOW_LOC_PARABOLOID_DEPTH) uniform vec3 depthParams;

flat in vec4 gPlane;
noperspective in vec3 gPoint;

void main() {
    // The inverse of (x, y) = r.xy / (1 + r.z) for a unit direction r.
    const vec2 xy = gl_FragCoord.xy * depthParams.z - 1.0;
    const float rr = dot(xy, xy);
    const vec3 r = vec3(2.0 * xy, 1.0 - rr) / (1.0 + rr);
    const float facing = dot(gPlane.xyz, r);
    const float distance = gPlane.w / facing;
    // Edge-on planes and intersections behind the light (a pixel the straight-edged
    // triangle covers but its curved image does not) keep the interpolated point.
    const bool exact = abs(facing) > 1e-6 && distance > 0.0 && !isinf(distance);
    const float d = depthParams.y / max(exact ? distance : length(gPoint), 1e-30) - depthParams.x;
    gl_FragDepth = clamp(d, 0.0, 1.0);
}
