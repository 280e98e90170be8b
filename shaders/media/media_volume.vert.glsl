// media.bounded.interval: the triangles of one spot light's volume (media_volume.comp.glsl's
// vertices) drawn without attributes: G^2 cells of two triangles, then four walls of G
// triangles from the light's position to the height field's border.
#include "../common/frame.glsl"
#include "media_bindings.h"

layout(std430, binding = MEDIA_VOLUME_SSBO) readonly buffer VolumeVertices {
    vec4 volumeVertices[];
};
layout(location = MEDIA_VOLUME_LOC_GRID) uniform ivec4 volumeGrid; // record, cell texels, cells per side, first

out vec3 viewPosition;

// The vertex (of the grid's (G + 1)^2, or the light's: index (G + 1)^2) of corner c of triangle t.
int volumeVertex(int t, int c, int cells) {
    const int row = cells + 1;
    if (t < 2 * cells * cells) {
        const int cell = t / 2, v00 = (cell / cells) * row + cell % cells;
        const ivec3 first = ivec3(v00, v00 + 1, v00 + row + 1), second = ivec3(v00, v00 + row + 1, v00 + row);
        return (t % 2 == 0 ? first : second)[c];
    }
    const int w = t - 2 * cells * cells, side = w / cells, s = w % cells + (c == 2 ? 1 : 0);
    if (c == 0) return row * row; // the light
    return side == 0 ? s : side == 1 ? cells * row + s : side == 2 ? s * row : s * row + cells;
}

void main() {
    const int cells = volumeGrid.z;
    viewPosition = volumeVertices[volumeGrid.w + volumeVertex(gl_VertexID / 3, gl_VertexID % 3, cells)].xyz;
    gl_Position = frame.projection * vec4(viewPosition, 1.0);
}
