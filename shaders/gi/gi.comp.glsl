// One-bounce indirect light at the GI resolution: one invocation per pixel, at the top-left
// G-buffer pixel of its block; when the result is filtered, also writes the guide for the
// filters. REFINE: one invocation per G-buffer pixel the upsampling listed
// (refine_list.glsl), computed as at full resolution into the full-resolution image. TILES:
// one group per tile with geometry (geometry_tiles.glsl).
//! Every permutation the module compiles (validated by glslangValidator at build time):
//! variant: METHOD=0 SCREEN_MARCH=0
//! variant: METHOD=0 SCREEN_MARCH=0 SCREEN_PEELED
//! variant: METHOD=0 SCREEN_MARCH=0 SCREEN_PEELED SCREEN_PEELED_OR_CONSTANT
//! variant: METHOD=0 SCREEN_MARCH=1
//! variant: METHOD=0 SCREEN_MARCH=1 SCREEN_PEELED
//! variant: METHOD=0 SCREEN_MARCH=1 SCREEN_PEELED SCREEN_PEELED_OR_CONSTANT
//! variant: METHOD=0 SCREEN_MARCH=2
//! variant: METHOD=0 SCREEN_MARCH=2 SCREEN_PEELED
//! variant: METHOD=0 SCREEN_MARCH=2 SCREEN_PEELED SCREEN_PEELED_OR_CONSTANT
//! variant: METHOD=1 TRAVERSAL=0
//! variant: METHOD=1 TRAVERSAL=1
//! variant: METHOD=1 TRAVERSAL=2
//! variant: METHOD=0 SCREEN_MARCH=0 REFINE
//! variant: METHOD=0 SCREEN_MARCH=0 SCREEN_PEELED REFINE
//! variant: METHOD=0 SCREEN_MARCH=0 SCREEN_PEELED SCREEN_PEELED_OR_CONSTANT REFINE
//! variant: METHOD=0 SCREEN_MARCH=1 REFINE
//! variant: METHOD=0 SCREEN_MARCH=1 SCREEN_PEELED REFINE
//! variant: METHOD=0 SCREEN_MARCH=1 SCREEN_PEELED SCREEN_PEELED_OR_CONSTANT REFINE
//! variant: METHOD=0 SCREEN_MARCH=2 REFINE
//! variant: METHOD=0 SCREEN_MARCH=2 SCREEN_PEELED REFINE
//! variant: METHOD=0 SCREEN_MARCH=2 SCREEN_PEELED SCREEN_PEELED_OR_CONSTANT REFINE
//! variant: METHOD=1 TRAVERSAL=0 REFINE
//! variant: METHOD=1 TRAVERSAL=1 REFINE
//! variant: METHOD=1 TRAVERSAL=2 REFINE
//! variant: METHOD=0 SCREEN_MARCH=2 RAY_LANES=16 REFINE
//! variant: METHOD=1 TRAVERSAL=2 RAY_LANES=16
//! variant: METHOD=0 SCREEN_MARCH=2 TILES
//! variant: METHOD=1 TRAVERSAL=1 TILES
#include "../common/sampling.glsl"
#include "../visibility/screen_march.glsl"
#include "gi_bindings.h"
#if METHOD == GI_METHOD_HYBRID
#include "../voxel/voxel_traversal.glsl"
#include "../voxel/surface_rays.glsl"
#endif
#include "../filters/refine_list.glsl"
#include "../common/ray_batch.glsl"
#if GI_WORKGROUP != FILTER_WORKGROUP
#error "the refinement dispatch and the ray lanes count FILTER_WORKGROUP^2 pixels a group"
#endif

layout(local_size_x = GI_WORKGROUP, local_size_y = GI_WORKGROUP, local_size_z = RAY_LANES) in;
layout(std140, binding = GI_PARAMS_UBO_BINDING) uniform GiBlock {
    GiParams gi;
};
layout(binding = GI_RADIANCE_UNIT) uniform sampler2D directRadiance;
layout(binding = GI_ALBEDO_UNIT) uniform sampler2D albedoTexture;
layout(binding = GI_OUT_IMAGE, rgba16f) writeonly uniform image2D integratorOut;
layout(binding = GI_GUIDE_OUT_IMAGE, rgba32f) writeonly uniform image2D guideOut;

// The radiance leaving the surface at the hit p + w t (w a unit direction, t a distance)
// toward p, read from the screen: the pixel the hit projects to, if that pixel shows it, its
// front side faces p, and the ray enters it from the front (w against its normal) no nearer
// than `entryFrom` to p, where it crosses the pixel's tangent plane. The screen march passes
// the distance of the sample before the hit, less half a step: a ray that went behind the
// visible surface elsewhere, through a side the camera does not see, hit that side, whose
// radiance is unknown (reading the visible top of a box for a ray that entered through its
// unseen back made glowing spots). Otherwise nothing is known: 0.
// "Shows it": the hit lies within `tolerance` of the tangent plane. Comparing depths at the
// pixel's centre instead refused hits on surfaces seen at a grazing angle, whose pixels span
// more depth than a fine voxel grid's tolerance. A pixel that shows a surface exactly edge-on
// (its plane holds the view ray) accepts any hit near that ray: the G-buffer does not say how
// far such a surface reaches.
vec3 giScreenRadiance(vec3 p, vec3 w, float t, float entryFrom, float tolerance) {
    const vec3 hit = p + w * t;
    ivec2 q;
    if (!screenPixelOf(hit, q)) return vec3(0.0);
    const float depth = texelFetch(visDepth, q, 0).r;
    if (isBackground(depth)) return vec3(0.0);
    const vec3 o = viewPositionFromDepth(pixelCenterUv(q), depth);
    const vec3 n = texelFetch(visNormal, q, 0).xyz;
    if (abs(dot(n, hit - o)) > tolerance) return vec3(0.0);
    const float front = dot(n, p - o), into = dot(n, w);
    // p in front of the plane and w going into it: the crossing is at front / -into > 0.
    if (!(front > 0.0 && into < 0.0) || front < entryFrom * -into) return vec3(0.0);
    return clampRadiance(texelFetch(directRadiance, q, 0).rgb);
}

// The sum of the radiance read over this batch's rays (ray_batch.glsl).
vec3 giRadianceSum(vec3 p, float depth, vec3 normal, float normalError, ivec2 pixel) {
    const vec2 rotation = pixelRotation(pixel, frame.sampleShift);
    const float jitter = pixelJitter(pixel, frame.sampleShift);
    const uint n = uint(gi.rayCount);
    const float radius = gi.radius;
    vec3 sum = vec3(0.0);
#if METHOD == GI_METHOD_HYBRID
    const VoxelSurfaceStart from = voxelSurfaceStart(p, depth, normal, normalError, gi.voxelStartOffset);
    const vec3 startVoxel = (gi.viewToVoxel * vec4(from.start, 1.0)).xyz;
#endif
    for (uint i = rayBatchFirst(); i < rayBatchEnd(); i += uint(RAY_LANES)) {
        const vec3 w = toFrame(cosineHemisphere(rotateSample(hammersley(i, n), rotation)), normal);
#if METHOD == GI_METHOD_SCREEN
        const float t = screenMarch(ScreenRayStart(p, normal, normalError), w, radius, gi.stepCount, jitter, gi.thickness); // distance
        // The hidden sample lies behind the surface it projects to: read that surface, if the
        // ray crossed it after the previous sample (a step of r / steps before, with half a
        // step of slack).
        const float entryFrom = t - 1.5 * radius / float(gi.stepCount);
        if (t >= 0.0) sum += giScreenRadiance(p, w, t, entryFrom, gi.thickness + radius);
#else
        // Only as far as the ray provably stays above the surface's own voxels
        // (surface_rays.glsl); a ray traced no farther reads nothing.
        float reach = voxelClearLength(from, normal, w, radius);
        if (!(reach > 0.0)) continue;
        const vec3 endVoxel = voxelTraceableEnd(gi.viewToVoxel, from.start, w, reach);
#if TRAVERSAL == VOXEL_METHOD_MARCH
        const VoxelHit hit = voxelTraceMarch(startVoxel, endVoxel, gi.stepCount, jitter);
#elif TRAVERSAL == VOXEL_METHOD_EXACT
        const VoxelHit hit = voxelTraceExact(startVoxel, endVoxel);
#else
        const VoxelHit hit = voxelTraceHierarchical(startVoxel, endVoxel);
#endif
        // The voxel hit is the entry into the first voxel the surface touches, so a ray that
        // meets the visible surface crosses its plane there or after (the march: up to a
        // step before, its sample being up to a step late). A crossing more than a voxel
        // diagonal (the slack of the tangent plane) before the hit means the ray went under
        // the visible surface and entered something the camera does not see.
        const float t = hit.t * reach;
        const float slack = gi.voxelStartOffset + (TRAVERSAL == VOXEL_METHOD_MARCH ? reach / float(gi.stepCount) : 0.0);
        if (hit.hit) sum += giScreenRadiance(from.start, w, t, t - slack, gi.thickness);
#endif
    }
    return sum;
}

ivec2 integratorSize() { return gi.size; }
int integratorScale() { return gi.scale; }
bool integratorWritesGuide() { return gi.writeGuide != 0; }
vec3 integratorSum(vec3 p, float depth, vec3 normal, float normalError, ivec2 pixel) {
    return giRadianceSum(p, depth, normal, normalError, pixel);
}
// E / pi: the directions are cosine-weighted.
vec3 integratorIncident(vec3 sum) { return sum / float(gi.rayCount); }

#include "../filters/rgb_integrator_main.glsl"
