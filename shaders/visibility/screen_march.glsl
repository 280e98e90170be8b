// Visibility in screen space: whether a view-space point is hidden behind the depth buffer,
// and the first such point along a ray. Needs frame.glsl's block (the G-buffer's camera) and
// the depth and normal textures at VIS_DEPTH_UNIT and VIS_NORMAL_UNIT.
//
// A depth pixel stands for a small piece of surface: its reconstructed point o with the
// G-buffer's normal n_o, extending `thickness` behind the front depth. A point s is hidden
// when it is behind that piece's tangent plane (dot(s - o, n_o) < 0, so a ray leaving a
// plane never hits the same plane, whatever the pixel grid) and at most `thickness` behind
// the front depth. Points outside the image or in front of the camera plane are visible:
// the border policy (nothing is known there).
#include "../common/depth.glsl"
#include "visibility_bindings.h"

layout(binding = VIS_DEPTH_UNIT) uniform sampler2D visDepth;
layout(binding = VIS_NORMAL_UNIT) uniform sampler2D visNormal;

// The pixel a view-space point projects to; false outside the image or behind the camera.
bool screenPixelOf(vec3 s, out ivec2 pixel) {
    const vec4 clip = frame.projection * vec4(s, 1.0);
    pixel = ivec2(-1);
    if (!(clip.w > 0.0)) return false;
    const vec2 uv = clip.xy / clip.w * 0.5 + 0.5;
    if (any(lessThan(uv, vec2(0.0))) || any(greaterThanEqual(uv, vec2(1.0)))) return false;
    pixel = min(ivec2(uv * vec2(frameSize())), frameSize() - 1);
    return true;
}

// Relative tolerance of the tangent-plane test: reconstructed positions carry float
// rounding of a few ulp of their magnitude.
const float kScreenPlaneTolerance = 4e-6;

// Whether s is hidden behind the depth buffer (see above).
bool screenHidden(vec3 s, float thickness) {
    ivec2 pixel;
    if (!screenPixelOf(s, pixel)) return false;
    const float depth = texelFetch(visDepth, pixel, 0).r;
    if (isBackground(depth)) return false;
    const vec3 o = viewPositionFromDepth(pixelCenterUv(pixel), depth);
    const vec3 n = texelFetch(visNormal, pixel, 0).xyz;
    const float scale = max(length(o), length(s));
    return dot(s - o, n) < -kScreenPlaneTolerance * scale && s.z >= o.z - thickness;
}

// The first of `steps` samples at distances radius (j + jitter) / steps, j = 0 .. steps - 1,
// along the unit direction w from p that is hidden; its distance, or -1 when none is.
float screenMarch(vec3 p, vec3 w, float radius, int steps, float jitter, float thickness) {
    for (int j = 0; j < steps; ++j) {
        const float t = radius * (float(j) + jitter) / float(steps);
        if (screenHidden(p + w * t, thickness)) return t;
    }
    return -1.0;
}
