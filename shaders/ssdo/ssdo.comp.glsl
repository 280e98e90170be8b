// Screen-space directional occlusion (Ritschel et al. 2009) at the integrator's resolution:
// one invocation per pixel, at the top-left G-buffer pixel of its block; when the result is
// filtered, also writes the guide for the filters. REFINE: the pixels the upsampling listed,
// at full resolution; TILES: one group per tile with geometry (as AO's integrator).
// Both passes take the same `rays` cosine-weighted directions and march each with `steps`
// depth-buffer samples out to the radius (steps = 1: the paper's one point at a random
// distance), so that a direction the direct pass finds open, the bounce finds open too.
//   PASS = SSDO_PASS_DIRECT: the mean of the environment's radiance over the open directions,
//     E / pi of the visible sky (the albedo multiplies it, here or after the filters).
//   PASS = SSDO_PASS_BOUNCE: the light of the occluders: each hidden sample stands for a patch
//     of area A_s = pi r^2 / N of the surface its pixel shows, which sends that pixel's
//     outgoing radiance toward p: (1/pi) Sum L_q min(A_s cos_s / d^2, omega_max) cos_r.
//! Every permutation the module compiles (validated by glslangValidator at build time):
//! variant: PASS=0 SCREEN_MARCH=0
//! variant: PASS=0 SCREEN_MARCH=0 SCREEN_PEELED
//! variant: PASS=0 SCREEN_MARCH=0 SCREEN_PEELED SCREEN_PEELED_OR_CONSTANT
//! variant: PASS=0 SCREEN_MARCH=1
//! variant: PASS=0 SCREEN_MARCH=1 SCREEN_PEELED
//! variant: PASS=0 SCREEN_MARCH=1 SCREEN_PEELED SCREEN_PEELED_OR_CONSTANT
//! variant: PASS=0 SCREEN_MARCH=2
//! variant: PASS=0 SCREEN_MARCH=2 SCREEN_PEELED
//! variant: PASS=0 SCREEN_MARCH=2 SCREEN_PEELED SCREEN_PEELED_OR_CONSTANT
//! variant: PASS=0 SCREEN_MARCH=0 EXTRA_VIEWS
//! variant: PASS=1 SCREEN_MARCH=0 SCREEN_PEELED EXTRA_VIEWS
//! variant: PASS=0 SCREEN_MARCH=0 EXTRA_VIEWS TILES
//! variant: PASS=0 SCREEN_MARCH=0 TILES
//! variant: PASS=0 SCREEN_MARCH=0 REFINE
//! variant: PASS=0 SCREEN_MARCH=0 RAY_LANES=16
//! variant: PASS=0 SCREEN_MARCH=0 RAY_LANES=4 TILES
//! variant: PASS=1 SCREEN_MARCH=0
//! variant: PASS=1 SCREEN_MARCH=0 SCREEN_PEELED
//! variant: PASS=1 SCREEN_MARCH=0 SCREEN_PEELED SCREEN_PEELED_OR_CONSTANT
//! variant: PASS=1 SCREEN_MARCH=1
//! variant: PASS=1 SCREEN_MARCH=1 SCREEN_PEELED
//! variant: PASS=1 SCREEN_MARCH=1 SCREEN_PEELED SCREEN_PEELED_OR_CONSTANT
//! variant: PASS=1 SCREEN_MARCH=2
//! variant: PASS=1 SCREEN_MARCH=2 SCREEN_PEELED
//! variant: PASS=1 SCREEN_MARCH=2 SCREEN_PEELED SCREEN_PEELED_OR_CONSTANT
//! variant: PASS=1 SCREEN_MARCH=0 TILES
//! variant: PASS=1 SCREEN_MARCH=0 REFINE
//! variant: PASS=1 SCREEN_MARCH=0 RAY_LANES=16
//! variant: PASS=1 SCREEN_MARCH=0 RAY_LANES=4 TILES
#include "../common/sampling.glsl"
#include "../visibility/screen_march.glsl"
#include "../environment/environment.glsl"
#include "ssdo_bindings.h"
#include "../filters/refine_list.glsl"
#include "../common/ray_batch.glsl"
#if SSDO_WORKGROUP != FILTER_WORKGROUP
#error "the refinement dispatch and the ray lanes count FILTER_WORKGROUP^2 pixels a group"
#endif

layout(local_size_x = SSDO_WORKGROUP, local_size_y = SSDO_WORKGROUP, local_size_z = RAY_LANES) in;
layout(std140, binding = SSDO_PARAMS_UBO_BINDING) uniform SsdoBlock {
    SsdoParams ssdo;
};
layout(binding = SSDO_SENDER_UNIT) uniform sampler2D senderRadiance;
#ifdef EXTRA_VIEWS
layout(std140, binding = SSDO_VIEWS_UBO_BINDING) uniform SsdoViewsBlock {
    SsdoViews views;
};
layout(binding = SSDO_EXTRA_DEPTH_UNIT) uniform sampler2DArray extraDepth;
layout(binding = SSDO_EXTRA_NORMAL_UNIT) uniform sampler2DArray extraNormal;

// Extra view k's verdict on main-view point s: 1 hidden (behind its surface, within
// `thickness`), -1 visible (in front of it, or nothing there), 0 no vote (outside the view,
// within its tolerance of the surface, or deeper than `thickness`).
int ssdoExtraVerdict(int k, vec3 s) {
    const vec3 sk = (views.mainToView[k] * vec4(s, 1.0)).xyz;
    const vec4 clip = frame.projection * vec4(sk, 1.0);
    if (!(clip.w > 0.0)) return 0;
    const vec2 uv = clip.xy / clip.w * 0.5 + 0.5;
    if (!(all(greaterThanEqual(uv, vec2(0.0))) && all(lessThan(uv, vec2(1.0))))) return 0;
    const ivec2 q = min(ivec2(uv * vec2(views.size)), views.size - 1);
    const float depth = texelFetch(extraDepth, ivec3(q, k), 0).r;
    if (isBackground(depth)) return -1;
    const vec3 o = viewPositionFromDepth((vec2(q) + 0.5) / vec2(views.size), depth);
    const float behind = -dot(sk - o, texelFetch(extraNormal, ivec3(q, k), 0).xyz);
    // The depth's reconstruction error and a thousandth of the radius (unit-free): a sample
    // on a surface seen at another pixel size is neither side of it.
    const float tolerance = 2.0 * depthReconstructionError(o, depth) + 1e-3 * ssdo.radius;
    if (behind > tolerance) return behind <= ssdo.thickness ? 1 : 0;
    return behind < -tolerance ? -1 : 0;
}

// The main view's verdict on s (projecting to pixel q), as ssdoExtraVerdict's: hidden as
// screenHiddenAt says; visible in front of the pixel's surface by more than the tolerance; no
// vote behind it deeper than `thickness` or within the tolerance.
int ssdoMainVerdict(vec3 s, ivec2 q, ScreenRayStart from) {
    if (screenHiddenAt(q, s, from, ssdo.thickness)) return 1;
    const float depth = texelFetch(visDepth, q, 0).r;
    if (isBackground(depth)) return -1;
    const vec3 o = viewPositionFromDepth(pixelCenterUv(q), depth);
    const float behind = -dot(s - o, texelFetch(visNormal, q, 0).xyz);
    return behind < -(2.0 * depthReconstructionError(o, depth) + 1e-3 * ssdo.radius) ? -1 : 0;
}

// The march over the main view and the extra ones: a sample is occluded when some view sees
// it hidden and none sees it in front of its surface (a view it lies outside of, or behind a
// surface deeper than `thickness`, has no vote). So an occluder off screen, or behind another
// one in the main view, is found through another view, and a gap behind a front surface that
// another view sees into stays open. A thin occluder that some view sees past is missed. View-space samples (the march
// setting is the main view's only). The distance of the first occluded sample, or -1.
float ssdoMarch(vec3 p, vec3 normal, float normalError, vec3 w, float jitter) {
    const ScreenRayStart from = ScreenRayStart(p, normal, normalError);
    float hitT = -1.0;
    for (int j = 0; j < ssdo.stepCount; ++j) {
        const float t = ssdo.radius * screenSampleT(j, ssdo.stepCount, jitter);
        const vec3 s = p + w * t;
        ivec2 q;
        const int main = screenPixelOf(s, q) ? ssdoMainVerdict(s, q, from) : 0;
        bool hidden = main > 0, visible = main < 0;
        for (int k = 0; k < views.count; ++k) {
            const int verdict = ssdoExtraVerdict(k, s);
            hidden = hidden || verdict > 0;
            visible = visible || verdict < 0;
        }
        if (hitT < 0.0 && hidden && !visible) hitT = t;
    }
    return hitT;
}
#endif
layout(binding = SSDO_ALBEDO_UNIT) uniform sampler2D albedoTexture;
layout(binding = SSDO_LIGHT_UNIT) uniform sampler2D lightRadiance;
layout(binding = SSDO_OUT_IMAGE, rgba16f) writeonly uniform image2D integratorOut;
layout(binding = SSDO_GUIDE_OUT_IMAGE, rgba32f) writeonly uniform image2D guideOut;

// What one occluding sample at distance t along w sends to p (the bounce): the patch of the
// surface its pixel q shows, at that surface's point o and normal, if o faces p and lies in
// p's hemisphere. The patch's solid angle A_s cos_s / d^2 is capped at what a disc of area
// A_s subtends on its axis from its own radius (SsdoParams::patchSolidAngle): as the scene
// and the radius scale together, so do A_s and d^2, and the cap is the same number.
vec3 ssdoSender(vec3 p, vec3 normal, vec3 w, float t) {
    ivec2 q;
    if (!screenPixelOf(p + w * t, q)) return vec3(0.0);
    const float depth = texelFetch(visDepth, q, 0).r;
    if (isBackground(depth)) return vec3(0.0);
    const vec3 o = viewPositionFromDepth(pixelCenterUv(q), depth);
    const vec3 sn = texelFetch(visNormal, q, 0).xyz;
    const vec3 v = o - p;
    const float d2 = dot(v, v);
    if (!(d2 > 0.0)) return vec3(0.0);
    const float d = sqrt(d2);
    const float cosR = dot(normal, v) / d, cosS = -dot(sn, v) / max(length(sn), 1e-30) / d;
    if (!(cosR > 0.0 && cosS > 0.0)) return vec3(0.0); // behind p, or seen from behind (back face)
    const float solidAngle = min(ssdo.patchArea * cosS / d2, ssdo.patchSolidAngle);
    vec3 radiance = texelFetch(senderRadiance, q, 0).rgb;
    if (ssdo.addLight != 0) radiance += texelFetch(lightRadiance, q, 0).rgb;
    return clampRadiance(radiance) * (solidAngle * cosR);
}

// This batch's sum (ray_batch.glsl): open directions' environment radiance, or the senders'.
vec3 ssdoSum(vec3 p, vec3 normal, float normalError, ivec2 pixel) {
    const vec2 rotation = pixelRotation(pixel, frame.sampleShift);
    const float jitter = pixelJitter(pixel, frame.sampleShift);
    const uint n = uint(ssdo.rayCount);
    const mat3 toWorld = mat3(ssdo.viewToWorld);
    vec3 sum = vec3(0.0);
    for (uint i = rayBatchFirst(); i < rayBatchEnd(); i += uint(RAY_LANES)) {
        const vec3 w = toFrame(cosineHemisphere(rotateSample(hammersley(i, n), rotation)), normal);
#ifdef EXTRA_VIEWS
        const float t = ssdoMarch(p, normal, normalError, w, jitter);
#else
        const float t = screenMarch(ScreenRayStart(p, normal, normalError), w, ssdo.radius, ssdo.stepCount, jitter, ssdo.thickness);
#endif
#if PASS == SSDO_PASS_DIRECT
        if (t < 0.0) sum += environmentRadiance(toWorld * w, ssdo.environmentLevel);
#else
        if (t >= 0.0) sum += ssdoSender(p, normal, w, t);
#endif
    }
    return sum;
}

ivec2 integratorSize() { return ssdo.size; }
int integratorScale() { return ssdo.scale; }
bool integratorWritesGuide() { return ssdo.writeGuide != 0; }
vec3 integratorSum(vec3 p, float depth, vec3 normal, float normalError, ivec2 pixel) {
    return ssdoSum(p, normal, normalError, pixel);
}
vec3 integratorIncident(vec3 sum) {
#if PASS == SSDO_PASS_DIRECT
    return sum / float(ssdo.rayCount); // cosine-weighted: E / pi
#else
    return ssdo.bounceStrength * sum / OBSCURA_PI;
#endif
}

#include "../filters/rgb_integrator_main.glsl"
