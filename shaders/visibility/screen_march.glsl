// Visibility in screen space: whether a view-space point is hidden behind the depth buffer,
// and the first such sample along a ray. Needs frame.glsl's block (the G-buffer's camera) and
// the depth and normal textures at VIS_DEPTH_UNIT and VIS_NORMAL_UNIT.
//
// A depth pixel stands for a small piece of surface: its reconstructed point o with the
// G-buffer's normal n_o, `thickness` deep behind its tangent plane (along n_o) or, with
// SCREEN_PEELED, down to the second depth layer (the surface behind it; the constant
// thickness where there is none), and with SCREEN_PEELED_OR_CONSTANT too down to the
// deeper of the two. A point s is hidden when it is behind that piece's tangent plane
// (dot(s - o, n_o) < 0, so a ray leaving a plane never hits the same plane, whatever the
// pixel grid; by more than the rounding of depth, positions and normals) and not beyond the
// piece's back. Points outside the image or in front of the
// camera plane are visible: the border policy (nothing is known there).
//
// Rays are sampled at t_j = (j + jitter) / steps, j = 0 .. steps - 1, of a segment p -> p + d,
// either as 3D points p + d t_j projected to their pixels (screenMarch), or in texture space
// (screenMarchTexture): homogeneous clip coordinates and view z interpolated linearly in t,
// the view point reconstructed from the texture coordinate. Both classify each sample with
// screenHiddenAt and so agree up to float rounding at pixel edges. With SCREEN_MARCH =
// VIS_MARCH_HIZ, screenMarchHiZ returns the texture-space march's first hidden sample
// exactly, skipping runs of samples whose view-z range misses a pyramid cell's bounds.
// SCREEN_MARCH (VIS_MARCH_*, View when not defined) picks what screenMarchSegment and
// screenMarch use.
#include "../common/depth.glsl"
#include "../common/math.glsl"
#include "visibility_bindings.h"

#ifndef SCREEN_MARCH
#define SCREEN_MARCH VIS_MARCH_VIEW
#endif

layout(binding = VIS_DEPTH_UNIT) uniform sampler2D visDepth;
layout(binding = VIS_NORMAL_UNIT) uniform sampler2D visNormal;
#ifdef SCREEN_PEELED
layout(binding = VIS_BACK_DEPTH_UNIT) uniform sampler2D visBackDepth;
#endif

// The pixel of a clip-space point; false outside the image or not in front of the camera.
bool screenPixelOfClip(vec4 clip, out ivec2 pixel) {
    pixel = ivec2(-1);
    if (!(clip.w > 0.0)) return false;
    const vec2 uv = clip.xy / clip.w * 0.5 + 0.5;
    // Inside as a positive test, so that NaN is outside: a clip coordinate can be Inf * 0 or
    // Inf / Inf where a segment's extent overflows float, and ivec2(NaN) is undefined.
    if (!(all(greaterThanEqual(uv, vec2(0.0))) && all(lessThan(uv, vec2(1.0))))) return false;
    pixel = min(ivec2(uv * vec2(frameSize())), frameSize() - 1);
    return true;
}

// The pixel a view-space point projects to; false outside the image or behind the camera.
bool screenPixelOf(vec3 s, out ivec2 pixel) { return screenPixelOfClip(frame.projection * vec4(s, 1.0), pixel); }

// How far from a tangent plane a point must be to count as behind or above it: float
// rounding of points of this magnitude, plus the reconstruction errors (depthReconstructionError)
// of the plane's point and of the one compared with it.
float screenPlaneTolerance(float magnitude, float reconstructionErrors) {
    return kPositionRounding * magnitude + reconstructionErrors;
}

// The start of a ray: its point, its pixel's stored normal (zero where unknown) and that
// normal's error (storedNormalError).
struct ScreenRayStart {
    vec3 p;
    vec3 n;
    float normalError;
};

// Each stored normal lies within its pixel's storedNormalError of the true one. A ray leaving a
// plane at `from` into the hemisphere of from's stored normal may reach s up to
// oError |from - o| + (fromError + oError) |s - from| behind another pixel o's stored
// tangent plane of the same plane: from - o lies in the true plane, off o's stored one by
// oError per unit length, and the two stored normals differ by at most the sum of their
// errors along the ray. Only a pixel that may lie on from's plane needs that: one farther
// from from's stored tangent plane than from's normal error (and the points' own errors,
// positionErrors) allow is another surface, which hides what is behind it.
float screenNormalSlack(ScreenRayStart from, vec3 s, vec3 o, float oError, float positionErrors) {
    const vec3 toO = o - from.p;
    const float distance = length(toO);
    if (abs(dot(toO, from.n)) > from.normalError * distance + positionErrors) return 0.0;
    return oError * distance + (from.normalError + oError) * lengthWithoutOverflow(s - from.p);
}

// Whether s, which projects to `pixel`, is hidden behind that pixel's piece of surface:
// behind its tangent plane, and at most `thickness` behind it (measured along the normal,
// so the test does not depend on how much depth one pixel's footprint spans) or, peeled,
// not beyond the back layer. `from`: the start of the ray s lies on (s itself for a point).
bool screenHiddenAt(ivec2 pixel, vec3 s, ScreenRayStart from, float thickness) {
    const float depth = texelFetch(visDepth, pixel, 0).r;
    const vec3 o = viewPositionFromDepth(pixelCenterUv(pixel), depth);
    const vec4 normalTexel = texelFetch(visNormal, pixel, 0);
    const vec3 n = normalTexel.xyz;
    const float behind = -dot(s - o, n);
    bool inside = behind <= thickness;
#ifdef SCREEN_PEELED
    const float back = texelFetch(visBackDepth, pixel, 0).r;
    const bool beforeBack = !isBackground(back) && s.z >= min(viewZFromDepth(back), o.z);
#ifdef SCREEN_PEELED_OR_CONSTANT
    inside = inside || beforeBack;
#else
    inside = isBackground(back) ? inside : beforeBack;
#endif
#endif
    // The ray's start carries the error of its own pixel's depth, taken as o's: a ray leaving
    // a surface meets its own plane's pixels first.
    const float depthErrors = 2.0 * depthReconstructionError(o, depth);
    const float positionErrors = screenPlaneTolerance(max(length(o), length(from.p)), depthErrors);
    const float errors = depthErrors + screenNormalSlack(from, s, o, storedNormalError(normalTexel), positionErrors);
    return !isBackground(depth) && behind > screenPlaneTolerance(max(length(o), lengthWithoutOverflow(s)), errors) && inside;
}

// Whether s, a point seen from `from`, is hidden behind the depth buffer (see above).
bool screenHidden(vec3 s, ScreenRayStart from, float thickness) {
    ivec2 pixel;
    return screenPixelOf(s, pixel) && screenHiddenAt(pixel, s, from, thickness);
}

float screenSampleT(int j, int steps, float jitter) { return (float(j) + jitter) / float(steps); }

// Texel fetches of classifying one sample inside the image (depth, normal, back layer).
#ifdef SCREEN_PEELED
const uint kScreenSampleFetches = 3u;
#else
const uint kScreenSampleFetches = 2u;
#endif

// 3D march of the segment p -> p + d: the parameter t_j of the first hidden sample, or -1;
// `fetches` counts texel fetches. The loop carries no early exit (see voxel_traversal.glsl
// on llvmpipe).
float screenMarchView(ScreenRayStart start, vec3 d, int steps, float jitter, float thickness, out uint fetches) {
    float hitT = -1.0;
    fetches = 0u;
    for (int j = 0; j < steps && hitT < 0.0; ++j) {
        const float t = screenSampleT(j, steps, jitter);
        const vec3 s = start.p + d * t;
        ivec2 pixel;
        if (screenPixelOf(s, pixel)) {
            fetches += kScreenSampleFetches;
            if (screenHiddenAt(pixel, s, start, thickness)) hitT = t;
        }
    }
    return hitT;
}

// A segment in texture space: clip coordinates and view z, both linear in t.
struct ScreenRay {
    vec4 clip0, clipDelta;
    float z0, zDelta;
};

ScreenRay screenRayOf(vec3 p, vec3 d) {
    return ScreenRay(frame.projection * vec4(p, 1.0), frame.projection * vec4(d, 0.0), p.z, d.z);
}

// The view point with texture coordinate uv at view z (the inverse of the projection).
vec3 viewPositionFromUvZ(vec2 uv, float z) {
    const vec2 xy = (uv * 2.0 - 1.0) * frame.rayScale + frame.rayOffset;
    return isPerspective() ? vec3(-z * xy, z) : vec3(xy, z);
}

// The texture-space sample at t: its pixel and its view point; false outside the image.
bool screenSampleAt(ScreenRay r, float t, out ivec2 pixel, out vec3 s) {
    const vec4 clip = r.clip0 + r.clipDelta * t;
    const bool inside = screenPixelOfClip(clip, pixel);
    s = inside ? viewPositionFromUvZ(clip.xy / clip.w * 0.5 + 0.5, r.z0 + r.zDelta * t) : vec3(0.0);
    return inside;
}

// 2D march of the segment p -> p + d in texture space: t_j of the first hidden sample, or -1.
float screenMarchTexture(ScreenRayStart start, vec3 d, int steps, float jitter, float thickness, out uint fetches) {
    const ScreenRay r = screenRayOf(start.p, d);
    float hitT = -1.0;
    fetches = 0u;
    for (int j = 0; j < steps && hitT < 0.0; ++j) {
        const float t = screenSampleT(j, steps, jitter);
        ivec2 pixel;
        vec3 s;
        if (screenSampleAt(r, t, pixel, s)) {
            fetches += kScreenSampleFetches;
            if (screenHiddenAt(pixel, s, start, thickness)) hitT = t;
        }
    }
    return hitT;
}

#if SCREEN_MARCH == VIS_MARCH_HIZ
// Per cell of level L (2^L x 2^L pixels): x = the nearest view z at which any point of the
// cell can be hidden, y = the farthest (hiz_build.comp.glsl). Built for one thickness.
layout(binding = VIS_HIZ_UNIT) uniform sampler2D visHiZ;

// The parameter t > t0 at which the projected segment crosses the screen line
// clip.c / clip.w = b (one coordinate), or 2 (beyond the segment) when it does not.
float screenLineCrossing(float c0, float dc, float w0, float dw, float b, float t0) {
    const float t = (b * w0 - c0) / (dc - b * dw);
    return t > t0 ? t : 2.0; // NaN (parallel) compares false
}

// Where the projected segment leaves the pixel box [lo, hi) after t0 (which is inside it).
float screenCellExit(ScreenRay r, vec2 lo, vec2 hi, float t0) {
    const vec2 ndcLo = lo / vec2(frameSize()) * 2.0 - 1.0, ndcHi = hi / vec2(frameSize()) * 2.0 - 1.0;
    const vec4 c = r.clip0, dc = r.clipDelta;
    float t = screenLineCrossing(c.x, dc.x, c.w, dc.w, ndcLo.x, t0);
    t = min(t, screenLineCrossing(c.x, dc.x, c.w, dc.w, ndcHi.x, t0));
    t = min(t, screenLineCrossing(c.y, dc.y, c.w, dc.w, ndcLo.y, t0));
    return min(t, screenLineCrossing(c.y, dc.y, c.w, dc.w, ndcHi.y, t0));
}

// The texture-space march through the pyramid: from sample j, the run of samples j..k in
// j's cell at the current level is skipped when its view-z range (exact: z is linear in t)
// misses the cell's bounds, after which the level goes up; otherwise the level goes down
// while the run holds more than j, and once it is j alone (k = j), or at level 0, j is
// classified as screenMarchTexture does. Not down to level 0 first: the levels below would
// bound only j, at a fetch and a cell exit each; on llvmpipe (128 x 128, ao.raymarch high,
// 16 steps) that made Hi-Z 1.62-1.70x the texture-space march's time on the Cornell box
// against 1.49x this way (benchmarks/README.md). k comes from the
// segment's exit from the cell and is kept only when sample k lands in the cell itself
// (else the run is j alone), so no sample outside the cell's bounds is ever skipped.
// Returns t of the first hidden sample or -1; `fetches` counts texel fetches.
float screenMarchHiZ(ScreenRayStart start, vec3 d, int steps, float jitter, float thickness, out uint fetches) {
    const ScreenRay r = screenRayOf(start.p, d);
    const int top = textureQueryLevels(visHiZ) - 1;
    float hitT = -1.0;
    fetches = 0u;
    int j = 0, level = 0;
    // Each iteration skips samples, classifies one or descends a level: bounded.
    const int guard = 4 * steps * (top + 2) + 8;
    for (int iteration = 0; iteration < guard && j < steps && hitT < 0.0; ++iteration) {
        const float t = screenSampleT(j, steps, jitter);
        ivec2 pixel;
        vec3 s;
        const bool inside = screenSampleAt(r, t, pixel, s);
        if (!inside) {
            j += 1; // outside the image: visible, nothing to fetch
            level = 0;
        } else {
            const ivec2 cell = pixel >> level;
            const vec2 bounds = texelFetch(visHiZ, cell, level).xy;
            fetches += 1u;
            const float exitT = screenCellExit(r, vec2(cell << level), vec2((cell + 1) << level), t);
            int k = clamp(int(ceil(exitT * float(steps) - jitter)) - 1, j, steps - 1);
            ivec2 lastPixel;
            vec3 lastS;
            const bool lastInside = screenSampleAt(r, screenSampleT(k, steps, jitter), lastPixel, lastS);
            if (!lastInside || any(notEqual(lastPixel >> level, cell))) k = j;
            const float zj = r.z0 + r.zDelta * t, zk = r.z0 + r.zDelta * screenSampleT(k, steps, jitter);
            const bool misses = min(zj, zk) > bounds.x || max(zj, zk) < bounds.y;
            if (misses) {
                j = k + 1;
                level = min(level + 1, top);
            } else if (level > 0 && k > j) {
                level -= 1;
            } else {
                fetches += kScreenSampleFetches;
                if (screenHiddenAt(pixel, s, start, thickness)) hitT = t;
                j += 1;
            }
        }
    }
    return hitT;
}
#endif

// The march SCREEN_MARCH selects over the segment p -> p + d: t of the first hidden sample or -1.
float screenMarchSegment(ScreenRayStart start, vec3 d, int steps, float jitter, float thickness, out uint fetches) {
#if SCREEN_MARCH == VIS_MARCH_TEXTURE
    return screenMarchTexture(start, d, steps, jitter, thickness, fetches);
#elif SCREEN_MARCH == VIS_MARCH_HIZ
    return screenMarchHiZ(start, d, steps, jitter, thickness, fetches);
#else
    return screenMarchView(start, d, steps, jitter, thickness, fetches);
#endif
}

// The distance along the unit direction w of the first hidden of `steps` samples out to
// `radius` from start.p, or -1 when none is.
float screenMarch(ScreenRayStart start, vec3 w, float radius, int steps, float jitter, float thickness) {
    uint fetches;
    const float t = screenMarchSegment(start, w * radius, steps, jitter, thickness, fetches);
    return t < 0.0 ? -1.0 : t * radius;
}
