// Ambient occlusion / obscurance at the AO resolution: one invocation per AO pixel, at the
// top-left G-buffer pixel of its block. When the result is filtered, also writes the guide
// (view normal, view z) that the blur and the upsampling weigh with. REFINE: one invocation
// per G-buffer pixel the upsampling listed (refine_list.glsl), computed as at full
// resolution and written into the full-resolution images. TILES: one group per tile with
// geometry (geometry_tiles.glsl).
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
//! variant: METHOD=1 SCREEN_MARCH=0
//! variant: METHOD=1 SCREEN_MARCH=0 SCREEN_PEELED
//! variant: METHOD=1 SCREEN_MARCH=0 SCREEN_PEELED SCREEN_PEELED_OR_CONSTANT
//! variant: METHOD=2
//! variant: METHOD=3 TRAVERSAL=0
//! variant: METHOD=3 TRAVERSAL=1
//! variant: METHOD=3 TRAVERSAL=2
//! variant: METHOD=0 SCREEN_MARCH=0 REFINE
//! variant: METHOD=0 SCREEN_MARCH=0 SCREEN_PEELED REFINE
//! variant: METHOD=0 SCREEN_MARCH=0 SCREEN_PEELED SCREEN_PEELED_OR_CONSTANT REFINE
//! variant: METHOD=0 SCREEN_MARCH=1 REFINE
//! variant: METHOD=0 SCREEN_MARCH=1 SCREEN_PEELED REFINE
//! variant: METHOD=0 SCREEN_MARCH=1 SCREEN_PEELED SCREEN_PEELED_OR_CONSTANT REFINE
//! variant: METHOD=0 SCREEN_MARCH=2 REFINE
//! variant: METHOD=0 SCREEN_MARCH=2 SCREEN_PEELED REFINE
//! variant: METHOD=0 SCREEN_MARCH=2 SCREEN_PEELED SCREEN_PEELED_OR_CONSTANT REFINE
//! variant: METHOD=1 SCREEN_MARCH=0 REFINE
//! variant: METHOD=1 SCREEN_MARCH=0 SCREEN_PEELED REFINE
//! variant: METHOD=1 SCREEN_MARCH=0 SCREEN_PEELED SCREEN_PEELED_OR_CONSTANT REFINE
//! variant: METHOD=2 REFINE
//! variant: METHOD=3 TRAVERSAL=0 REFINE
//! variant: METHOD=3 TRAVERSAL=1 REFINE
//! variant: METHOD=3 TRAVERSAL=2 REFINE
//! variant: METHOD=0 SCREEN_MARCH=2 SCREEN_PEELED RAY_LANES=16
//! variant: METHOD=1 SCREEN_MARCH=0 RAY_LANES=16 REFINE
//! variant: METHOD=2 RAY_LANES=16
//! variant: METHOD=3 TRAVERSAL=2 RAY_LANES=2
//! variant: METHOD=3 TRAVERSAL=2 RAY_LANES=16 REFINE
//! variant: METHOD=0 SCREEN_MARCH=0 TILES
//! variant: METHOD=1 SCREEN_MARCH=0 SCREEN_PEELED TILES
//! variant: METHOD=2 TILES
//! variant: METHOD=3 TRAVERSAL=2 RAY_LANES=16 TILES
#include "../common/sampling.glsl"
#include "../visibility/screen_march.glsl"
#include "ao_common.glsl"
#if METHOD == AO_METHOD_VOXEL
#include "../voxel/voxel_traversal.glsl"
#include "../voxel/surface_rays.glsl"
#endif
#include "../filters/refine_list.glsl"
#include "../common/ray_batch.glsl"
#if AO_WORKGROUP != FILTER_WORKGROUP
#error "the refinement dispatch and the ray lanes count FILTER_WORKGROUP^2 pixels a group"
#endif

layout(local_size_x = AO_WORKGROUP, local_size_y = AO_WORKGROUP, local_size_z = RAY_LANES) in;
layout(binding = AO_OUT_IMAGE, r16f) writeonly uniform image2D aoOut;
layout(binding = AO_BENT_OUT_IMAGE, rgba16f) writeonly uniform image2D bentOut;
layout(binding = AO_GUIDE_OUT_IMAGE, rgba32f) writeonly uniform image2D guideOut;

// The estimate is 1 - occluded / count rather than sum(V) / count: GLSL allows division 2.5
// ULP of error, so n / n may come out below 1, and a float-to-half store may round it toward
// zero to 0.99951. With nothing occluded the quotient is 0 / count, exactly 0. Sums over the
// rays (or slices) of this ray batch (ray_batch.glsl).
struct Estimate {
    float occluded; // sum of 1 - V (or 1 - rho) over the samples; horizon: open - visible arcs
    vec3 bent;  // sum of the unoccluded directions (cosine-weighted)
    float count;    // samples; horizon: the open arcs
};

// Direction i of n about the normal, in the weighting the settings ask for.
vec3 aoDirection(uint i, uint n, vec2 rotation, vec3 normal) {
    const vec2 u = rotateSample(hammersley(i, n), rotation);
    return toFrame(aoCosine() ? cosineHemisphere(u) : uniformHemisphere(u), normal);
}

// Adds one ray's result: 1 - V (or 1 - rho at the hit), and to the bent normal the direction when
// open (weighted by the cosine when the directions are uniform, so both estimate the
// cosine-weighted mean).
void aoAdd(inout Estimate e, vec3 w, vec3 normal, float hitDistance) {
    const bool hit = hitDistance >= 0.0;
    e.occluded += hit ? 1.0 - aoHitValue(hitDistance) : 0.0;
    if (!hit) e.bent += aoCosine() ? w : w * max(dot(w, normal), 0.0);
    e.count += 1.0;
}

#if METHOD == AO_METHOD_RAYMARCH
Estimate aoEstimate(vec3 p, vec3 normal, float normalError, ivec2 pixel, ivec2 fullPixel) {
    Estimate e = Estimate(0.0, vec3(0.0), 0.0);
    const vec2 rotation = pixelRotation(pixel, frame.sampleShift);
    const float jitter = pixelJitter(pixel, frame.sampleShift);
    const uint n = uint(ao.rayCount);
    for (uint i = rayBatchFirst(); i < rayBatchEnd(); i += uint(RAY_LANES)) {
        const vec3 w = aoDirection(i, n, rotation, normal);
        aoAdd(e, w, normal, screenMarch(ScreenRayStart(p, normal, normalError), w, ao.radius, ao.stepCount, jitter, ao.thickness));
    }
    return e;
}
#elif METHOD == AO_METHOD_POINTS
// Crytek-style: points in the ball of radius r cut to the normal's hemisphere, along the
// directions aoDirection weighs (uniform ones make the points uniform in the half-ball) at
// distance r u^(1/3), u the 3D Hammersley set's third coordinate; a hidden point counts as
// occluded at its distance.
Estimate aoEstimate(vec3 p, vec3 normal, float normalError, ivec2 pixel, ivec2 fullPixel) {
    Estimate e = Estimate(0.0, vec3(0.0), 0.0);
    const vec2 rotation = pixelRotation(pixel, frame.sampleShift);
    const float jitter = pixelJitter(pixel, frame.sampleShift);
    const uint n = uint(ao.rayCount);
    for (uint i = rayBatchFirst(); i < rayBatchEnd(); i += uint(RAY_LANES)) {
        const vec3 w = aoDirection(i, n, rotation, normal);
        const float u = rotateSample(radicalInverse3(i), jitter);
        const float d = ao.radius * pow(max(u, 1e-6), 1.0 / 3.0);
        aoAdd(e, w, normal, screenHidden(p + w * d, ScreenRayStart(p, normal, normalError), ao.thickness) ? d : -1.0);
    }
    return e;
}
#elif METHOD == AO_METHOD_HORIZON
// The cosine-weighted visible arc of one slice, between horizon angles h1 <= h2 measured
// from the view direction, for a normal at angle g in the slice plane (GTAO's inner integral).
float aoArc(float h1, float h2, float g) {
    return 0.25 * (-cos(2.0 * h1 - g) + cos(g) + 2.0 * h1 * sin(g)) +
           0.25 * (-cos(2.0 * h2 - g) + cos(g) + 2.0 * h2 * sin(g));
}

// The slice's share of the bent normal, as (along v, along the slice's positive side): the
// integral over the visible arc [h1, h2] of the direction cos(t) v + sin(t) side, weighted as
// aoArc weighs it (cos(t - g) |sin t|), in closed form: F(h1) + F(h2) - 2 F(0) with the
// antiderivatives below (|sin t| changes sign at 0). Summed over the slices times their
// weights it is the cosine-weighted sum of the open directions, as the other methods' bent
// normals are.
vec2 aoBentArc(float h1, float h2, float g) {
    const float cg = cos(g), sg = sin(g);
    const vec2 h = vec2(h1, h2);
    const vec2 c = cos(h), s = sin(h);
    const vec2 alongV = 0.25 * (cg * (-cos(3.0 * h) / 3.0 - c) + sg * (s - sin(3.0 * h) / 3.0));
    const vec2 alongSide = cg * s * s * s / 3.0 + sg * (c * c * c / 3.0 - c);
    return vec2(alongV.x + alongV.y + 2.0 * cg / 3.0, alongSide.x + alongSide.y + 4.0 * sg / 3.0);
}

// A point of the pixel's own plane at distance len lies up to len * normalError off the
// stored tangent plane (storedNormalError: 2^-10 for the half floats the G-buffer stores,
// which may round toward zero, as llvmpipe's do; more for a host's 8-bit normals and for
// normals reconstructed from depth).
// Without this margin a floor's own depth samples passed the tangent-plane test on an open
// floor seen at 16 degrees in an orthographic view (48 x 40 pixels, the radius 10 pixels),
// and the samples' rounding to pixels off the slice made horizons of them: AO 0.997; with
// 8-bit host normals, AO 0.97 on most of a floor.

// Slices through the view direction at angles phi; on each side `steps` depth samples out
// to the radius projected at p find the highest point within the radius above p's tangent
// plane. The result is normalized by the same sum for an open hemisphere, so a plane with
// nothing above it is exactly 1 for any number of slices. Slices are this batch's "rays".
Estimate aoEstimate(vec3 p, vec3 normal, float normalError, ivec2 pixel, ivec2 fullPixel) {
    Estimate e = Estimate(0.0, vec3(0.0), 0.0);
    const vec2 rotation = pixelRotation(pixel, frame.sampleShift);
    const float jitter = pixelJitter(pixel, frame.sampleShift);
    const vec3 v = viewDirectionTo(p);
    const int slices = max(ao.rayCount / 2, 1);
    // Pixels per world unit at p (perspective: the projection's y scale over the distance).
    const float pixelsPerUnit = 0.5 * float(frameSize().y) * abs(frame.projection[1][1]) /
                                (isPerspective() ? max(-p.z, 1e-30) : 1.0);
    // A screen direction's view-space direction: the same but for the axes the projection
    // mirrors (p00 or p11 < 0, e.g. a host's for glClipControl(GL_UPPER_LEFT), whose rows run
    // top down). Times exactly 1 otherwise.
    const vec2 screenToView = vec2(frame.projection[0][0] < 0.0 ? -1.0 : 1.0, frame.projection[1][1] < 0.0 ? -1.0 : 1.0);
    const float reach = min(ao.radius * pixelsPerUnit, kFloatMax); // the radius in G-buffer pixels
    // Offsets are cut to twice the image's larger side, which any direction leaves the image
    // by: a float past the int range converts to an undefined int (GLSL 4.50, 5.4.1), and
    // radii far beyond the scene reach that (and Inf) in pixels.
    const float farthestOffset = 2.0 * float(max(frameSize().x, frameSize().y));
    const float pError = depthReconstructionError(p, texelFetch(visDepth, fullPixel, 0).r);
    for (int s = int(rayBatchFirst()); s < int(rayBatchEnd()); s += RAY_LANES) {
        const float phi = OBSCURA_PI * (float(s) + rotation.x) / float(slices);
        const vec2 dir = vec2(cos(phi), sin(phi)), viewDir = dir * screenToView;
        // The slice plane holds v and the screen direction; `axis` is its normal, and
        // cross(v, axis) points from v toward +dir: angles are positive that way.
        const vec3 axis = safeNormalize(cross(vec3(viewDir, 0.0), v), vec3(0.0, 0.0, 1.0));
        const vec3 projected = normal - axis * dot(normal, axis);
        const float weight = length(projected);
        if (!(weight > 0.0)) continue;
        const vec3 np = projected / weight;
        const vec3 toSide = cross(v, axis);
        const float g = sign(dot(np, toSide)) * acos(clamp(dot(np, v), -1.0, 1.0));
        float h[2];
        for (int side = 0; side < 2; ++side) {
            const float sgn = side == 0 ? -1.0 : 1.0;
            float best = -1.0; // cosine of the horizon angle from v; -1: none found
            for (int j = 0; j < ao.stepCount; ++j) {
                const float offset = min(reach * (float(j) + jitter) / float(ao.stepCount), farthestOffset);
                const ivec2 q = fullPixel + ivec2(round(sgn * dir * max(offset, 1.0)));
                if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, frameSize()))) break; // border: open
                const float depth = texelFetch(visDepth, q, 0).r;
                if (isBackground(depth)) continue;
                const vec3 o = viewPositionFromDepth(pixelCenterUv(q), depth), d = o - p;
                const float len = length(d);
                // Within the radius and above p's tangent plane (beyond float rounding, the
                // depth buffer's precision and the stored normal's).
                const float errors = depthReconstructionError(o, depth) + pError + len * normalError;
                if (!(len > 0.0) || len > ao.radius || dot(d, normal) <= screenPlaneTolerance(length(p) * 4.0, errors)) continue;
                best = max(best, dot(d / len, v));
            }
            // Angle from v toward the side; limited by the hemisphere of the normal.
            const float limit = g + sgn * 0.5 * OBSCURA_PI;
            const float found = sgn * acos(clamp(best, -1.0, 1.0));
            h[side] = side == 0 ? max(found, limit) : min(found, limit);
        }
        // The same arcs for an open slice: open - visible is exactly 0 there.
        const float open = weight * aoArc(g - 0.5 * OBSCURA_PI, g + 0.5 * OBSCURA_PI, g);
        e.occluded += open - weight * aoArc(h[0], h[1], g);
        e.count += open;
        // Equal steps of phi turn the slice plane about v by unequal angles psi where v leans
        // off the screen's normal (perspective, off centre): dpsi/dphi = v.z / (1 - (d.v)^2),
        // d = (viewDir, 0). Weighted so, the slices integrate over the hemisphere and an open
        // plane's bent normal is its normal (at 0.067 rad without, 48 x 40 pixels at 50
        // degrees); the AO above keeps its own (documented) slice integral.
        const float alongDir = dot(viewDir, v.xy);
        const float turn = v.z / max(1.0 - alongDir * alongDir, 1e-6);
        const vec2 bent = aoBentArc(h[0], h[1], g);
        e.bent += turn * weight * (bent.x * v + bent.y * toSide);
    }
    return e;
}
#else
// Rays of length r through the voxel grid from a start lifted off the surface's voxels, each
// only as far as it provably stays above them (surface_rays.glsl).
Estimate aoEstimate(vec3 p, vec3 normal, float normalError, ivec2 pixel, ivec2 fullPixel) {
    Estimate e = Estimate(0.0, vec3(0.0), 0.0);
    const vec2 rotation = pixelRotation(pixel, frame.sampleShift);
    const float jitter = pixelJitter(pixel, frame.sampleShift);
    const VoxelSurfaceStart from =
        voxelSurfaceStart(p, texelFetch(visDepth, fullPixel, 0).r, normal, normalError, ao.voxelStartOffset);
    const vec3 startVoxel = (ao.viewToVoxel * vec4(from.start, 1.0)).xyz;
    const uint n = uint(ao.rayCount);
    for (uint i = rayBatchFirst(); i < rayBatchEnd(); i += uint(RAY_LANES)) {
        const vec3 w = aoDirection(i, n, rotation, normal);
        float reach = voxelClearLength(from, normal, w, ao.radius);
        if (!(reach > 0.0)) {
            aoAdd(e, w, normal, -1.0);
            continue;
        }
        const vec3 endVoxel = voxelTraceableEnd(ao.viewToVoxel, from.start, w, reach);
        // One traversal per permutation (TRAVERSAL = VOXEL_METHOD_*): the loop body stays small.
#if TRAVERSAL == VOXEL_METHOD_MARCH
        const VoxelHit hit = voxelTraceMarch(startVoxel, endVoxel, ao.stepCount, jitter);
#elif TRAVERSAL == VOXEL_METHOD_EXACT
        const VoxelHit hit = voxelTraceExact(startVoxel, endVoxel);
#else
        const VoxelHit hit = voxelTraceHierarchical(startVoxel, endVoxel);
#endif
        aoAdd(e, w, normal, hit.hit ? hit.t * reach : -1.0);
    }
    return e;
}
#endif

// No return before rayLanesSum, which every invocation of the group must reach.
void main() {
    ivec2 pixel, full;
    const bool mine = integratorPixel(aoSize(), aoScale(), pixel, full);
#ifdef REFINE
    const bool guide = false; // the listed pixels are written at full resolution, unfiltered
#else
    const bool guide = aoGuide();
#endif
    const float depth = texelFetch(visDepth, full, 0).r;
    const vec4 normalTexel = texelFetch(visNormal, full, 0);
    const bool background = isBackground(depth) || normalTexel.a == 0.0;
    vec3 p = vec3(0.0), normal = vec3(0.0, 0.0, 1.0);
    Estimate own = Estimate(0.0, vec3(0.0), 0.0);
    if (mine && !background) {
        p = viewPositionFromDepth(pixelCenterUv(full), depth);
        normal = safeNormalize(normalTexel.xyz, viewDirectionTo(p));
        own = aoEstimate(p, normal, storedNormalError(normalTexel), pixel, full);
    }
    const RayBatchPartial lanes = rayLanesSum(RayBatchPartial(vec4(own.occluded, own.bent), vec4(own.count)));
    if (!mine || rayLane() != 0u) return;
    if (background) {
        imageStore(aoOut, pixel, vec4(1.0));
        if (aoBent()) imageStore(bentOut, pixel, vec4(0.0));
        if (guide) imageStore(guideOut, pixel, vec4(0.0));
        return;
    }
    const uint slot = rayBatchSlot(pixel, aoSize());
    const RayBatchPartial sums = rayBatchMerged(slot, lanes);
    if (!rayBatchLast()) {
        rayBatchKeep(slot, sums);
        return;
    }
    const Estimate e = Estimate(sums.a.x, sums.a.yzw, sums.b.x);
    const float value = e.count > 0.0 ? clamp(1.0 - e.occluded / e.count, 0.0, 1.0) : 1.0;
    imageStore(aoOut, pixel, vec4(roundedToHalf(value)));
    if (aoBent()) imageStore(bentOut, pixel, vec4(safeNormalize(e.bent, normal), 1.0));
    if (guide) imageStore(guideOut, pixel, vec4(normal, p.z));
}
