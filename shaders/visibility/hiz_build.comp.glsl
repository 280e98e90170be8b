// The pyramid of screenMarchHiZ. LEVEL 0: per pixel, x = the nearest view z at which a
// point that projects into the pixel can be behind the pixel's tangent plane, y = the
// farthest at which it is still inside the piece of surface (screenHiddenAt). Other levels:
// the max of x and the min of y over the (up to) 2 x 2 cells below.
//! variant: LEVEL0
//! variant: LEVEL0 SCREEN_PEELED
//! variant: LEVEL0 SCREEN_PEELED SCREEN_PEELED_OR_CONSTANT
//! variant: REDUCE
#include "screen_march.glsl"

layout(local_size_x = VIS_WORKGROUP_2D, local_size_y = VIS_WORKGROUP_2D) in;
layout(binding = VIS_HIZ_WRITE_IMAGE, rg32f) writeonly uniform image2D hizOut;
#ifndef LEVEL0 // REDUCE
layout(binding = VIS_HIZ_READ_IMAGE, rg32f) readonly uniform image2D hizIn;
#endif
layout(location = VIS_LOC_THICKNESS) uniform float thickness;

const float kHuge = 3.0e38;
// Slack on both bounds, relative to the magnitudes the bounds are computed from (not to the
// bound itself, which may be near 0): they must hold for the marcher's float samples, whose
// reconstruction and interpolation round differently from this pass.
const float kBoundSlack = 1e-4;

#ifdef LEVEL0
// View z where the view ray through texture coordinate uv meets the plane through o with
// normal n, when the ray reaches the plane from its front side; kHuge otherwise (no bound).
float planeZAlongRay(vec2 uv, vec3 o, vec3 n) {
    const vec2 xy = (uv * 2.0 - 1.0) * frame.rayScale + frame.rayOffset;
    if (isPerspective()) {
        const vec3 d = vec3(xy, -1.0); // the ray's point at view z = -1
        const float dn = dot(d, n);
        return dn < -1e-6 * length(d) ? -dot(o, n) / dn : kHuge;
    }
    return n.z > 1e-6 ? (dot(o, n) - dot(xy, n.xy)) / n.z : kHuge;
}

// The extreme view z over the pixel's footprint of the plane through q with normal n
// (extreme at a corner: 1/z is linear in screen space for a plane); `nearest` picks the
// max, else the min. `none` where some corner's ray does not reach the plane from its front.
float footprintPlaneZ(ivec2 pixel, vec3 q, vec3 n, bool nearest, float none) {
    float z = nearest ? -kHuge : kHuge;
    bool bounded = true;
    for (int c = 0; c < 4; ++c) {
        const vec2 corner = (vec2(pixel) + vec2(c & 1, c >> 1)) / vec2(frameSize());
        const float cornerZ = planeZAlongRay(corner, q, n);
        bounded = bounded && cornerZ < kHuge;
        z = nearest ? max(z, cornerZ) : min(z, cornerZ);
    }
    return bounded ? z : none;
}

vec2 pixelBounds(ivec2 pixel) {
    const float depth = texelFetch(visDepth, pixel, 0).r;
    if (isBackground(depth)) return vec2(-kHuge, kHuge); // nothing is hidden here
    const vec3 o = viewPositionFromDepth(pixelCenterUv(pixel), depth);
    const vec3 n = texelFetch(visNormal, pixel, 0).xyz;
    // Hidden means beyond the tangent plane along the view ray, and not beyond the plane
    // `thickness` further back (or the back layer, or the deeper of both).
    const float nearest = max(o.z, footprintPlaneZ(pixel, o, n, true, kHuge));
    float farthest = footprintPlaneZ(pixel, o - n * thickness, n, false, -kHuge);
#ifdef SCREEN_PEELED
    const float back = texelFetch(visBackDepth, pixel, 0).r;
    const float backZ = min(viewZFromDepth(back), o.z);
#ifdef SCREEN_PEELED_OR_CONSTANT
    farthest = isBackground(back) ? farthest : min(farthest, backZ); // either interval
#else
    farthest = isBackground(back) ? farthest : backZ;
#endif
#endif
    const float scale = length(o) + thickness;
    return vec2(nearest + kBoundSlack * (abs(nearest) + scale), farthest - kBoundSlack * (abs(farthest) + scale));
}
#endif

void main() {
    const ivec2 cell = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(cell, imageSize(hizOut)))) return;
#ifdef LEVEL0
    // The pyramid is padded to powers of two; padding is background.
    const bool inImage = all(lessThan(cell, frameSize()));
    imageStore(hizOut, cell, vec4(inImage ? pixelBounds(cell) : vec2(-kHuge, kHuge), 0.0, 0.0));
#else
    const ivec2 below = imageSize(hizIn);
    vec2 bounds = vec2(-kHuge, kHuge);
    for (int c = 0; c < 4; ++c) {
        const ivec2 child = cell * 2 + ivec2(c & 1, c >> 1);
        if (all(lessThan(child, below))) {
            const vec2 b = imageLoad(hizIn, child).xy;
            bounds = vec2(max(bounds.x, b.x), min(bounds.y, b.y));
        }
    }
    imageStore(hizOut, cell, vec4(bounds, 0.0, 0.0));
#endif
}
