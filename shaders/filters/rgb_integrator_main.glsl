// main() of the integrators whose value is RGB radiance (IndirectLight, DirectionalOcclusion):
// one invocation per pixel at the integrator's resolution (at the top-left G-buffer pixel of
// its block), or per listed pixel (REFINE), or per tile with geometry (TILES); the ray
// lanes and batches (ray_batch.glsl); background pixels 0; the guide for the filters. Included
// last, after the module declared:
//   ivec2 integratorSize(); int integratorScale(); bool integratorWritesGuide();
//   vec3 integratorSum(vec3 p, float depth, vec3 normal, float normalError, ivec2 pixel):
//     this batch's sum over its rays;
//   vec3 integratorIncident(vec3 sum): the incident radiance from the sum over every ray;
//   image2D integratorOut (rgba16f), image2D guideOut (rgba32f), sampler2D albedoTexture.

// No return before rayLanesSum, which every invocation of the group must reach.
void main() {
    ivec2 pixel, full;
    const bool mine = integratorPixel(integratorSize(), integratorScale(), pixel, full);
#ifdef REFINE
    const bool guide = false; // the listed pixels are written at full resolution, unfiltered
#else
    const bool guide = integratorWritesGuide();
#endif
    const float depth = texelFetch(visDepth, full, 0).r;
    const vec4 normalTexel = texelFetch(visNormal, full, 0);
    const bool background = isBackground(depth) || normalTexel.a == 0.0;
    vec3 p = vec3(0.0), normal = vec3(0.0, 0.0, 1.0), own = vec3(0.0);
    if (mine && !background) {
        p = viewPositionFromDepth(pixelCenterUv(full), depth);
        normal = safeNormalize(normalTexel.xyz, viewDirectionTo(p));
        own = integratorSum(p, depth, normal, storedNormalError(normalTexel), pixel);
    }
    const RayBatchPartial lanes = rayLanesSum(RayBatchPartial(vec4(own, 0.0), vec4(0.0)));
    if (!mine || rayLane() != 0u) return;
    if (background) {
        imageStore(integratorOut, pixel, vec4(0.0));
        if (guide) imageStore(guideOut, pixel, vec4(0.0));
        return;
    }
    const uint slot = rayBatchSlot(pixel, integratorSize());
    const RayBatchPartial sums = rayBatchMerged(slot, lanes);
    if (!rayBatchLast()) {
        rayBatchKeep(slot, sums);
        return;
    }
    // A filtered result is the incident term alone: the filters weigh by depth and normal only,
    // so an albedo multiplied in here would be blurred across texture edges and, at a reduced
    // resolution, taken from the block's top-left pixel for the whole block. They multiply
    // each G-buffer pixel's own albedo in after the last step (FilterImages::modulate).
    const vec3 albedo = guide ? vec3(1.0) : clampAlbedo(texelFetch(albedoTexture, full, 0).rgb);
    imageStore(integratorOut, pixel, roundedToHalf(vec4(clampRadiance(albedo * integratorIncident(sums.a.rgb)), 1.0)));
    if (guide) imageStore(guideOut, pixel, vec4(normal, p.z));
}
