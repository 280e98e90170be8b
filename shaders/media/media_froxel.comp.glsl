// media.froxel: volumetric fog in a grid of froxels (frustum voxels: tiles of the screen
// times slices of view depth z_k = froxelRange (k / slices)^2, denser near the camera).
// INJECT: per froxel, at its centre, the light scattered toward the camera per unit length
//   S = Sum_lights sigma_s p L_i T(x, light) V(x) and sigma_t (many lights, one evaluation
//   per froxel instead of per pixel and step), each times the slice's length along the tile's
//   centre ray (what a half float holds at any scene scale).
// INTEGRATE: per tile column, front to back with the energy-conserving step along the
//   tile's centre ray: texel k holds the radiance scattered between the camera and z_k
//   (texel 0: none), in place.
// RESOLVE: per pixel, the integrated radiance at its surface's view depth (clamped to the
//   range), interpolated between the slices' ends and bilinearly between tiles.
//! Every permutation the module compiles (validated by glslangValidator at build time):
//! variant: INJECT
//! variant: INJECT SHADOWS
//! variant: INTEGRATE
//! variant: RESOLVE
#include "../common/depth.glsl"
#include "../gbuffer/gbuffer_bindings.h"
#include "../gbuffer/light_irradiance.glsl"
#ifdef SHADOWS
#include "../shadows/shadow_sample.glsl"
#endif
#include "media_common.glsl"
#include "media_shadow.glsl"

// View distance (-z) where slice boundary s (continuous, 0 to slices) lies, and back.
float froxelZ(float s) { return media.froxelRange * (s / float(media.froxels.z)) * (s / float(media.froxels.z)); }
float froxelSlice(float z) { return float(media.froxels.z) * sqrt(clamp(z / media.froxelRange, 0.0, 1.0)); }

// The view ray through texture coordinate uv (unit direction; from the origin, or from the
// image plane's point for an orthographic camera), scaled so that its z is -1.
vec3 froxelRay(vec2 uv, out vec3 origin) {
    const vec3 q = viewPositionFromDepth(uv, 0.5);
    origin = isPerspective() ? vec3(0.0) : vec3(q.xy, 0.0);
    return isPerspective() ? q / -q.z : vec3(0.0, 0.0, -1.0);
}

vec2 froxelTileUv(ivec2 tile) { return (vec2(tile) + 0.5) / vec2(media.froxels.xy); }

#ifdef INJECT
layout(local_size_x = MEDIA_FROXEL_WORKGROUP, local_size_y = MEDIA_FROXEL_WORKGROUP, local_size_z = MEDIA_FROXEL_WORKGROUP) in;
layout(binding = MEDIA_OUT_IMAGE, rgba16f) writeonly uniform image3D sourceOut;
layout(binding = MEDIA_DEPTH_OUT_IMAGE, rgba16f) writeonly uniform image3D extinctionOut;

void main() {
    const ivec3 froxel = ivec3(gl_GlobalInvocationID);
    if (any(greaterThanEqual(froxel, media.froxels))) return;
    vec3 origin;
    const vec3 ray = froxelRay(froxelTileUv(froxel.xy), origin);
    const vec3 viewDirection = normalize(ray);
    const vec3 x = origin + ray * froxelZ(float(froxel.z) + 0.5);
    const vec3 xw = mediaToWorld(x);
    vec3 scattering, extinction;
    mediaCoefficientsAt(xw, scattering, extinction);
    vec3 source = vec3(0.0);
    for (int i = 0; i < media.lightCount && any(greaterThan(scattering, vec3(0.0))); ++i) {
        vec3 toLight;
        float distance;
        const vec3 e = mediaLightAt(i, x, toLight, distance);
        const vec3 tau = mediaOpticalDepth(xw, mediaDirectionToWorld(toLight), distance);
        source += mediaScatteringPhase(xw, dot(toLight, viewDirection)) * e * (mediaLightVisibility(i, x, toLight) * exp(-tau));
    }
    // Texel k + 1 holds slice k: texel 0 is the camera's end, which INTEGRATE zeroes. Both are
    // stored times the slice's length along the tile's ray (radiance, and optical depth): per
    // unit length they scale with the scene's unit, and a half float would round a large
    // scene's 1e-6 per unit to its subnormals.
    const float sliceLength = (froxelZ(float(froxel.z + 1)) - froxelZ(float(froxel.z))) * length(ray);
    const ivec3 texel = froxel + ivec3(0, 0, 1);
    imageStore(sourceOut, texel, roundedToHalf(vec4(clampRadiance(source * sliceLength), 1.0)));
    imageStore(extinctionOut, texel, roundedToHalf(vec4(clamp(extinction * sliceLength, vec3(0.0), vec3(kHalfMax)), 1.0)));
}
#endif

#ifdef INTEGRATE
layout(local_size_x = MEDIA_WORKGROUP, local_size_y = MEDIA_WORKGROUP, local_size_z = 1) in;
layout(binding = MEDIA_OUT_IMAGE, rgba16f) uniform image3D grid;
layout(binding = MEDIA_DEPTH_OUT_IMAGE, rgba16f) readonly uniform image3D extinctionGrid;

void main() {
    const ivec2 tile = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(tile, media.froxels.xy))) return;
    vec3 radiance = vec3(0.0), tau = vec3(0.0);
    imageStore(grid, ivec3(tile, 0), vec4(0.0, 0.0, 0.0, 1.0));
    for (int k = 0; k < media.froxels.z; ++k) {
        const ivec3 texel = ivec3(tile, k + 1);
        // The slice's source times its length, and its optical depth (INJECT).
        const vec3 source = imageLoad(grid, texel).rgb, stepTau = imageLoad(extinctionGrid, texel).rgb;
        radiance += exp(-tau) * source * oneMinusExpOverX(stepTau);
        tau += stepTau;
        imageStore(grid, texel, roundedToHalf(vec4(clampRadiance(radiance), 1.0)));
    }
}
#endif

#ifdef RESOLVE
layout(local_size_x = MEDIA_WORKGROUP, local_size_y = MEDIA_WORKGROUP, local_size_z = 1) in;
layout(binding = MEDIA_DEPTH_UNIT) uniform sampler2D depthTexture;
layout(binding = MEDIA_FROXEL_READ_UNIT) uniform sampler3D integrated;
layout(binding = MEDIA_OUT_IMAGE, rgba16f) writeonly uniform image2D scatteringOut;
layout(binding = MEDIA_DEPTH_OUT_IMAGE, rgba16f) writeonly uniform image2D depthOut;

void main() {
    const ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(pixel, media.size))) return;
    const float depth = texelFetch(depthTexture, pixel, 0).r;
    const MediaRay r = mediaViewRay(pixel, depth);
    const float z = isBackground(depth) ? media.froxelRange : -viewPositionFromDepth(pixelCenterUv(pixel), depth).z;
    // Texel k holds the slices up to boundary k: slice coordinate s lies at texel coordinate s.
    const vec2 uv = pixelCenterUv(pixel);
    const float w = (froxelSlice(z) + 0.5) / float(media.froxels.z + 1);
    const vec3 radiance = texture(integrated, vec3(uv, w)).rgb;
    const vec3 ow = mediaToWorld(r.origin), ww = mediaDirectionToWorld(r.direction);
    imageStore(scatteringOut, pixel, roundedToHalf(vec4(clampRadiance(radiance), 1.0)));
    imageStore(depthOut, pixel, mediaStoredDepth(mediaOpticalDepth(ow, ww, r.end)));
}
#endif
