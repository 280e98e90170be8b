// media.bounded.volume: a spot light's lit volume rebuilt from its shadow map (after McCool
// 2000), as a closed mesh in the camera's view space: the map's depths as a height field over
// cells of C x C texels, and four walls from the light's position to the field's border. A
// point of the medium is lit only inside this volume, so the view ray's lit intervals lie
// between its first and last crossing of the mesh (media_volume.frag.glsl).
//
// Conservative by construction: each vertex takes the farthest depth of the cells around it,
// plus the map's bias, so every triangle lies at or behind every texel of its cell (a
// planar triangle's 1/depth is a convex mix of its corners'); the fine test
// (media_shadow.glsl) can only find a subset of the volume lit. Cells where the map holds
// nothing (no caster out to its far plane) count as lit (as media_shadow.glsl takes them):
// their vertices go to the cap distance, past every medium.
//
// Two dispatches per light: CELLS, the farthest distance each cell's texels hold (one read of
// each texel); then one invocation per vertex, the farthest of its (up to) four cells. Vertex
// (a, b), a, b in [0, G], at index first + b (G + 1) + a; the light's position after them.
//! variant:
//! variant: CELLS
#include "../shadows/shadow_sample.glsl"
#include "media_bindings.h"

layout(local_size_x = MEDIA_WORKGROUP, local_size_y = MEDIA_WORKGROUP, local_size_z = 1) in;
layout(binding = SHADOW_DEPTH_READ_UNIT) uniform sampler2DArray shadowDepthRead; // nearest, no comparison
layout(std430, binding = MEDIA_VOLUME_SSBO) writeonly buffer VolumeVertices {
    vec4 volumeVertices[];
};
layout(location = MEDIA_VOLUME_LOC_GRID) uniform ivec4 volumeGrid; // record, cell texels, cells per side, first
layout(location = MEDIA_VOLUME_LOC_CAP) uniform float volumeCap;
layout(binding = MEDIA_CELLS_IMAGE, r32f) uniform image2D cellFarthest; // G x G

#ifdef CELLS
// The farthest distance along the map's axis that cell `cell`'s texels hold (volumeCap where
// one of them holds nothing).
void main() {
    const int k = volumeGrid.x, size = volumeGrid.y, cells = volumeGrid.z;
    const ivec2 cell = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(cell, ivec2(cells)))) return;
    const float far = shadowLights[k].cascades[0].depthMapping.w, layer = shadowLights[k].cascades[0].layer;
    const ivec2 lo = cell * size, hi = min(lo + size, ivec2(shadowLights[k].resolution));
    float farthest = 0.0;
    for (int y = lo.y; y < hi.y; ++y)
        for (int x = lo.x; x < hi.x; ++x) {
            const float d = shadowDistance(k, 0, texelFetch(shadowDepthRead, ivec3(x, y, int(layer)), 0).r);
            // The cleared depth is the far plane; rounding may put it a hair before.
            farthest = d < far * (1.0 - 1e-4) ? max(farthest, d) : volumeCap; // the cap is past far
        }
    imageStore(cellFarthest, cell, vec4(farthest));
}
#else
// The farthest of the (up to four) cells around vertex `corner`.
float farthestAround(ivec2 corner) {
    const int cells = volumeGrid.z;
    float farthest = 0.0;
    for (int i = 0; i < 4; ++i) {
        const ivec2 cell = corner - 1 + ivec2(i & 1, i >> 1);
        if (all(greaterThanEqual(cell, ivec2(0))) && all(lessThan(cell, ivec2(cells))))
            farthest = max(farthest, imageLoad(cellFarthest, cell).r);
    }
    return farthest;
}

void main() {
    const int k = volumeGrid.x, cells = volumeGrid.z, first = volumeGrid.w;
    const ivec2 corner = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThan(corner, ivec2(cells)))) return;
    const vec3 light = shadowLights[k].light, axis = shadowLights[k].spotAxis;
    if (corner == ivec2(0)) volumeVertices[first + (cells + 1) * (cells + 1)] = vec4(light, 1.0);

    // media_shadow.glsl compares the point moved toward the light by the constant bias and
    // one texel (texelSize per unit distance): lit out to (stored + bias) / (1 - texelSize)
    // along the axis. 1e-3 more for the float rounding of the stored and compared depths. A
    // texel of half a unit or more (a map of a few texels over a wide cone) bounds nothing.
    const float stored = farthestAround(corner);
    const float texel = shadowLights[k].cascades[0].texelSize;
    const bool bounded = stored != volumeCap && texel < 0.5;
    const float along = bounded ? min((stored + shadowLights[k].constantBias) / (1.0 - texel) * (1.0 + 1e-3), volumeCap) : volumeCap;
    // The corner's direction: the point of the map's ray through it on the far plane (window
    // depth b / far - a), back in view space; a point far from the light keeps the direction's
    // rounding small.
    const vec2 uv = min(vec2(corner * volumeGrid.y) / float(shadowLights[k].resolution), vec2(1.0));
    const vec4 m = shadowLights[k].cascades[0].depthMapping;
    const vec4 p = inverse(shadowLights[k].cascades[0].viewToLight) * vec4(2.0 * uv - 1.0, m.y / m.w - m.x, 1.0);
    const vec3 direction = normalize(p.xyz / p.w - light);
    volumeVertices[first + corner.y * (cells + 1) + corner.x] = vec4(light + direction * (along / max(dot(direction, axis), 1e-6)), 1.0);
}
#endif
