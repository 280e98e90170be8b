// Reflective shadow map texel (Dachsbacher and Stamminger 2005): the flux the surface seen
// through this texel reflects, its normal and its position, all in world space.
//   flux = albedo * (the power through the texel): directional E s^2 (s: texel side, world
//   units); spot I cone(theta) s^2 cos^3(theta) (s: texel side on the image plane at unit
//   distance, so s^2 cos^3 is the texel's solid angle). Watts, RGB.
//   normal: the triangle's geometric normal, facing the light (meshes need no normals).
#include "../common/math.glsl"
#include "shadow_bindings.h"

layout(location = SHADOW_LOC_RSM_ALBEDO) uniform vec3 albedo;
layout(location = SHADOW_LOC_RSM_LIGHT) uniform vec4 lightPosition; // xyz: spot position or the direction light travels; w: SHADOW_LIGHT_*
layout(location = SHADOW_LOC_RSM_POWER) uniform vec4 power;         // rgb: color * intensity; w: s
layout(location = SHADOW_LOC_RSM_SPOT) uniform vec4 spotAxis;       // xyz: unit axis; w: unused
layout(location = SHADOW_LOC_RSM_CONE) uniform vec2 spotCos;        // cos(inner), cos(outer)

in vec3 vWorld;

layout(location = 0) out vec4 outFlux;
layout(location = 1) out vec4 outNormal;
layout(location = 2) out vec4 outPosition;

void main() {
    const bool spot = int(lightPosition.w) == SHADOW_LIGHT_SPOT;
    const vec3 toLight = spot ? safeNormalize(lightPosition.xyz - vWorld, -spotAxis.xyz) : -lightPosition.xyz;
    vec3 n = safeNormalize(cross(dFdx(vWorld), dFdy(vWorld)), toLight);
    n = dot(n, toLight) < 0.0 ? -n : n;
    const float c = dot(-toLight, spotAxis.xyz); // spot: cos of the angle to the axis
    const float texel = power.w * power.w;
    const float share = spot ? texel * c * c * c * spotCone(c, spotCos.x, spotCos.y) : texel;
    outFlux = vec4(albedo * power.rgb * share, 1.0);
    outNormal = vec4(n, 1.0);
    outPosition = vec4(vWorld, 1.0);
}
