// Joint bilateral upsampling to the G-buffer's resolution: the four low-resolution pixels
// around each G-buffer pixel, weighted bilinearly and by guideWeight against the pixel's own
// view depth and normal. Where no neighbour is similar, the one nearest in depth is taken.
// Background pixels get the background value (and no direction).
//
// One invocation writes a 2 x 2 quad of G-buffer pixels. With an even scale the quad's four
// pixels share the same four low-resolution neighbours, so each channel of those neighbours
// (and each channel of the quad's own depth and normal) is one textureGather. That is 13
// gathers per quad (5 without a direction) instead of 56 texel fetches (40). On llvmpipe,
// where every fetch is a per-lane load, that took a quarter off this pass at 512x512
// (5.8 -> 4.3 ms without a direction, less with one); on GPUs it cuts fetch instructions.
//! variant: RGB
#include "../visibility/screen_march.glsl"
#include "filter_common.glsl"

layout(local_size_x = FILTER_WORKGROUP, local_size_y = FILTER_WORKGROUP) in;
layout(binding = FILTER_GUIDE_UNIT) uniform sampler2D guide;
layout(binding = FILTER_VALUE_UNIT) uniform sampler2D valueIn;
layout(binding = FILTER_DIRECTION_UNIT) uniform sampler2D directionIn;
layout(binding = FILTER_VALUE_IMAGE, FILTER_FORMAT) writeonly uniform image2D valueOut;
layout(binding = FILTER_DIRECTION_IMAGE, rgba16f) writeonly uniform image2D directionOut;

// One low-resolution neighbour: its guide (normal, z; z = 0: background), value, direction.
struct Neighbour {
    vec4 guide;
    FILTER_VALUE value;
    vec3 direction;
};

// The running weighted sums for one G-buffer pixel, and the neighbour nearest in depth.
struct Blend {
    FILTER_VALUE sum, nearest;
    vec3 direction, nearestDirection;
    float total, nearestDz;
};

// textureGather returns the 2 x 2 texels around its point in the order x: (0, 1),
// y: (1, 1), z: (1, 0), w: (0, 0) from the lower corner. The point between texel `corner` and
// `corner` + (1, 1) selects exactly them; the clamp-to-edge sampler repeats the last row and
// column past the image, as clamping the coordinates would.
vec2 gatherPoint(ivec2 corner, ivec2 size) { return (vec2(corner) + 1.0) / vec2(size); }

#ifdef RGB
#define GATHER_VALUES(uv)                                                                                              \
    vec4 vr = textureGather(valueIn, uv, 0), vg = textureGather(valueIn, uv, 1), vb = textureGather(valueIn, uv, 2), \
         va = textureGather(valueIn, uv, 3)
#define VALUE_AT(c) vec4(vr.c, vg.c, vb.c, va.c)
#else
#define GATHER_VALUES(uv) vec4 vr = textureGather(valueIn, uv, 0)
#define VALUE_AT(c) vr.c
#endif

void accumulate(inout Blend b, Neighbour nb, float bilinear, vec3 n, float z) {
    const bool usable = nb.guide.w != 0.0;
    const float w = usable ? bilinear * guideWeight(n, z, nb.guide.xyz, nb.guide.w) : 0.0;
    b.sum += w * nb.value;
    b.direction += w * nb.direction;
    b.total += w;
    const float dz = abs(nb.guide.w - z);
    if (usable && dz < b.nearestDz) {
        b.nearestDz = dz;
        b.nearest = nb.value;
        b.nearestDirection = nb.direction;
    }
}

// Single exit: Mesa 22.3 llvmpipe miscompiles early returns in inlined code (see
// voxel_traversal.glsl). `f`: the pixel's bilinear position between the neighbours.
void writePixel(ivec2 pixel, float depth, vec4 normalTexel, vec2 f, Neighbour n00, Neighbour n10, Neighbour n01,
                Neighbour n11) {
    const bool background = isBackground(depth) || normalTexel.a == 0.0;
    const float z = background ? 1.0 : viewZFromDepth(depth);
    const vec3 n = normalTexel.xyz;
    Blend b = Blend(FILTER_VALUE(0.0), FILTER_VALUE(filterParams.weights.z), vec3(0.0), n, 0.0, 1e30);
    accumulate(b, n00, (1.0 - f.x) * (1.0 - f.y), n, z);
    accumulate(b, n10, f.x * (1.0 - f.y), n, z);
    accumulate(b, n01, (1.0 - f.x) * f.y, n, z);
    accumulate(b, n11, f.x * f.y, n, z);
    const bool weighted = b.total > 1e-6;
    const FILTER_VALUE blended = filterFinish(weighted ? b.sum / b.total : b.nearest);
    const bool inside = all(lessThan(pixel, frameSize())); // odd sizes: the quad's far half is outside
    if (inside) imageStore(valueOut, pixel, vec4(background ? FILTER_VALUE(filterParams.weights.z) : blended));
    if (inside && filterHasDirection()) {
        const vec3 direction = safeNormalize(weighted ? b.direction : b.nearestDirection, n);
        imageStore(directionOut, pixel, background ? vec4(0.0) : vec4(direction, 1.0));
    }
}

void main() {
    const ivec2 p00 = 2 * ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(p00, frameSize()))) return;
    const int s = filterScale(); // 2 or 4: even, so the whole quad has the same lower neighbour
    const ivec2 base = p00 / s;
    // Low-resolution pixel i covers G-buffer pixels [i s, i s + s) and was computed at i s.
    const vec2 f00 = vec2(p00 - base * s) / float(s), step = vec2(1.0 / float(s));

    const vec2 lowUv = gatherPoint(base, filterLowSize());
    const vec4 gx = textureGather(guide, lowUv, 0), gy = textureGather(guide, lowUv, 1);
    const vec4 gz = textureGather(guide, lowUv, 2), gw = textureGather(guide, lowUv, 3);
    GATHER_VALUES(lowUv);
    vec4 dx = vec4(0.0), dy = vec4(0.0), dz = vec4(0.0);
    if (filterHasDirection()) {
        dx = textureGather(directionIn, lowUv, 0);
        dy = textureGather(directionIn, lowUv, 1);
        dz = textureGather(directionIn, lowUv, 2);
    }
    const Neighbour n00 = Neighbour(vec4(gx.w, gy.w, gz.w, gw.w), VALUE_AT(w), vec3(dx.w, dy.w, dz.w));
    const Neighbour n10 = Neighbour(vec4(gx.z, gy.z, gz.z, gw.z), VALUE_AT(z), vec3(dx.z, dy.z, dz.z));
    const Neighbour n01 = Neighbour(vec4(gx.x, gy.x, gz.x, gw.x), VALUE_AT(x), vec3(dx.x, dy.x, dz.x));
    const Neighbour n11 = Neighbour(vec4(gx.y, gy.y, gz.y, gw.y), VALUE_AT(y), vec3(dx.y, dy.y, dz.y));

    const vec2 fullUv = gatherPoint(p00, frameSize());
    const vec4 depth = textureGather(visDepth, fullUv, 0);
    const vec4 nx = textureGather(visNormal, fullUv, 0), ny = textureGather(visNormal, fullUv, 1);
    const vec4 nz = textureGather(visNormal, fullUv, 2), na = textureGather(visNormal, fullUv, 3);
    writePixel(p00, depth.w, vec4(nx.w, ny.w, nz.w, na.w), f00, n00, n10, n01, n11);
    writePixel(p00 + ivec2(1, 0), depth.z, vec4(nx.z, ny.z, nz.z, na.z), f00 + vec2(step.x, 0.0), n00, n10, n01, n11);
    writePixel(p00 + ivec2(0, 1), depth.x, vec4(nx.x, ny.x, nz.x, na.x), f00 + vec2(0.0, step.y), n00, n10, n01, n11);
    writePixel(p00 + ivec2(1, 1), depth.y, vec4(nx.y, ny.y, nz.y, na.y), f00 + step, n00, n10, n01, n11);
}
