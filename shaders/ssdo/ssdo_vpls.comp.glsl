// SSDO's instant radiosity, at the G-buffer's resolution: virtual point lights from the
// lights' reflective shadow maps (one per cell of a grid over each map, the cell's flux at
// its centre texel), each seen through the same screen-space test as the shadow correction
// (ShadowMaskSettings' contactSteps samples, contactThickness thin) along the whole segment
// to it. A VPL of flux Phi and normal n_v at distance d gives the irradiance
// Phi max(0, n_v.w) max(0, n.-w) / (pi d^2), d^2 at least the cell's area over pi (a disc of
// that area never gives more than its exitance): a pixel next to a VPL stays bounded, and the
// bound scales with the scene. The result, times albedo / pi, is added to the bounce's (BOUNCE).
//! Every permutation the module compiles (validated by glslangValidator at build time):
//! variant:
//! variant: BOUNCE
//! variant: BOUNCE SCREEN_MARCH=1 SCREEN_PEELED
#include "../common/sampling.glsl"
#include "../visibility/screen_march.glsl"
#include "ssdo_bindings.h"

layout(local_size_x = SSDO_WORKGROUP, local_size_y = SSDO_WORKGROUP, local_size_z = 1) in;
layout(std140, binding = SSDO_PARAMS_UBO_BINDING) uniform SsdoBlock {
    SsdoParams ssdo;
};
layout(std140, binding = SSDO_VPLS_UBO_BINDING) uniform SsdoVplsBlock {
    SsdoVpls vpls;
};
layout(binding = SSDO_RSM_FLUX_UNIT) uniform sampler2DArray rsmFlux;
layout(binding = SSDO_RSM_NORMAL_UNIT) uniform sampler2DArray rsmNormal;
layout(binding = SSDO_RSM_POSITION_UNIT) uniform sampler2DArray rsmPosition;
layout(binding = SSDO_INDIRECT_TERM_UNIT) uniform sampler2D indirectTerm;
layout(binding = SSDO_ALBEDO_UNIT) uniform sampler2D albedoTexture;
layout(binding = SSDO_OUT_IMAGE, rgba16f) writeonly uniform image2D indirectOut;

// The texel of cell (i, j) of the grid, and its neighbour one cell on in x and in y.
ivec2 vplTexel(int i, int j) {
    const int cell = vpls.resolution / vpls.grid;
    return ivec2(i, j) * cell + cell / 2;
}

vec3 vplIrradiance(vec3 p, vec3 n, float normalError, ivec2 pixel) {
    const mat4 toView = frame.view;
    const float jitter = pixelJitter(pixel, frame.sampleShift);
    const int cell = vpls.resolution / vpls.grid;
    vec3 e = vec3(0.0);
    for (int l = 0; l < vpls.layerCount; ++l) {
        const int layer = vpls.layers[l / 4][l % 4];
        for (int j = 0; j < vpls.grid; ++j)
            for (int i = 0; i < vpls.grid; ++i) {
                const ivec2 t = vplTexel(i, j);
                const vec4 flux = texelFetch(rsmFlux, ivec3(t, layer), 0);
                if (!(flux.a > 0.0)) continue; // nothing seen through this texel
                const vec3 x = (toView * vec4(texelFetch(rsmPosition, ivec3(t, layer), 0).xyz, 1.0)).xyz;
                const vec3 nv = normalize(mat3(toView) * texelFetch(rsmNormal, ivec3(t, layer), 0).xyz);
                // The cell's area from its neighbours' positions (the last cells look back).
                const ivec2 tx = vplTexel(i + (i + 1 < vpls.grid ? 1 : -1), j), ty = vplTexel(i, j + (j + 1 < vpls.grid ? 1 : -1));
                const vec3 ax = (toView * vec4(texelFetch(rsmPosition, ivec3(tx, layer), 0).xyz, 1.0)).xyz - x;
                const vec3 ay = (toView * vec4(texelFetch(rsmPosition, ivec3(ty, layer), 0).xyz, 1.0)).xyz - x;
                const float area = length(cross(ax, ay));
                const vec3 v = x - p;
                const float d2 = dot(v, v);
                if (!(d2 > 0.0)) continue;
                const float d = sqrt(d2);
                const vec3 w = v / d;
                const float cosP = dot(n, w), cosV = -dot(nv, w);
                if (!(cosP > 0.0 && cosV > 0.0)) continue;
                // The march stops a cell's size short of the VPL: it stands for its whole cell,
                // whose own surface (seen from behind by the camera, perhaps) is no occluder.
                const float reach = d - sqrt(area);
                if (reach > 0.0 && screenMarch(ScreenRayStart(p, n, normalError), w, reach, ssdo.contactSteps, jitter,
                                               ssdo.contactThickness) >= 0.0)
                    continue;
                // The cell's flux: its centre texel's times the texels it stands for.
                const vec3 phi = flux.rgb * float(cell * cell);
                e += phi * (cosP * cosV / (OBSCURA_PI * max(d2, area / OBSCURA_PI)));
            }
    }
    return e;
}

void main() {
    const ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(pixel, frameSize()))) return;
    const float depth = texelFetch(visDepth, pixel, 0).r;
    const vec4 normalTexel = texelFetch(visNormal, pixel, 0);
    if (isBackground(depth) || normalTexel.a == 0.0) {
        imageStore(indirectOut, pixel, vec4(0.0));
        return;
    }
    const vec3 p = viewPositionFromDepth(pixelCenterUv(pixel), depth);
    const vec3 n = safeNormalize(normalTexel.xyz, viewDirectionTo(p));
    const vec3 albedo = clampAlbedo(texelFetch(albedoTexture, pixel, 0).rgb);
    vec3 radiance = albedo * (1.0 / OBSCURA_PI) * vplIrradiance(p, n, storedNormalError(normalTexel), pixel);
#ifdef BOUNCE
    radiance += texelFetch(indirectTerm, pixel, 0).rgb;
#endif
    imageStore(indirectOut, pixel, roundedToHalf(vec4(clampRadiance(radiance), 1.0)));
}
