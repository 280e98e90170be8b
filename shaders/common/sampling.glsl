// Sampling shared by every integrator, so that comparisons between methods are fair:
// Hammersley points with a per-pixel Cranley-Patterson rotation read from a tiled random
// texture, cosine-weighted and uniform hemisphere mappings, and a tangent frame without a
// degenerate normal. src/core/sampling.hpp mirrors these formulas on the CPU for tests.
#include "common_bindings.h"
#include "math.glsl"

layout(binding = OBSCURA_NOISE_TEXTURE_UNIT) uniform sampler2D noiseTexture; // RG32F, tiled

// Van der Corput in base 2: the bits of i mirrored behind the binary point.
float radicalInverse2(uint i) { return float(bitfieldReverse(i)) * 2.3283064365386963e-10; }

// Van der Corput in base 3: the ternary digits of i mirrored behind the point. The third
// coordinate of the 3D Hammersley set (i / n, base 2, base 3); a base-2 function of i would
// tie it to the second (their leading digits would be functions of the same low bits of i).
float radicalInverse3(uint i) {
    uint mirrored = 0u, scale = 1u;
    for (; i > 0u && scale < 1162261467u; i /= 3u) { // 3^19: the digits of any 32-bit i
        mirrored = mirrored * 3u + i % 3u;
        scale *= 3u;
    }
    return min(float(mirrored) / float(scale), 0.99999994); // past 3^15 the quotient may round to 1
}

// Point i of the n-point Hammersley set in [0, 1)^2.
vec2 hammersley(uint i, uint n) { return vec2(float(i) / float(n), radicalInverse2(i)); }

// The pixel's Cranley-Patterson offset in [0, 1)^2 (the texture tiles the screen).
vec2 pixelRotation(ivec2 pixel) { return texelFetch(noiseTexture, pixel & (OBSCURA_NOISE_SIZE - 1), 0).rg; }

// u + offset wrapped into [0, 1) (fract could round 1 - 2^-25 up to 1).
vec2 rotateSample(vec2 u, vec2 offset) {
    const vec2 v = u + offset;
    return min(v - floor(v), vec2(0.99999994));
}
float rotateSample(float u, float offset) { return rotateSample(vec2(u), vec2(offset)).x; }

// The pixel's rotation and its offset along rays (independent of the rotation) in a frame
// whose sampling is shifted by `frameShift` (FrameData::sampleShift: 0 for frame index 0, then
// the R3 sequence), so that successive frames rotate every pixel's points anew.
vec2 pixelRotation(ivec2 pixel, vec3 frameShift) { return rotateSample(pixelRotation(pixel), frameShift.xy); }
float pixelJitter(ivec2 pixel, vec3 frameShift) {
    return rotateSample(pixelRotation(pixel + ivec2(OBSCURA_NOISE_SIZE / 2, 7)).x, frameShift.z);
}

// Cosine-weighted direction about +z (pdf cos / pi): the disc point of radius sqrt(u.x)
// lifted onto the hemisphere.
vec3 cosineHemisphere(vec2 u) {
    const float r = sqrt(u.x), phi = 2.0 * OBSCURA_PI * u.y;
    return vec3(r * cos(phi), r * sin(phi), sqrt(max(1.0 - u.x, 0.0)));
}

// Uniform direction about +z (pdf 1 / (2 pi)).
vec3 uniformHemisphere(vec2 u) {
    const float z = u.x, r = sqrt(max(1.0 - z * z, 0.0)), phi = 2.0 * OBSCURA_PI * u.y;
    return vec3(r * cos(phi), r * sin(phi), z);
}

// An orthonormal frame (t, b, n) for a unit n, continuous except across n.z = 0's sign and
// exact for n = (0, 0, +-1) (Duff et al. 2017, "Building an orthonormal basis, revisited").
void tangentFrame(vec3 n, out vec3 t, out vec3 b) {
    const float s = n.z >= 0.0 ? 1.0 : -1.0; // -0 counts as +: no division by zero below
    const float a = -1.0 / (s + n.z);
    const float c = n.x * n.y * a;
    t = vec3(1.0 + s * n.x * n.x * a, s * c, -s * n.x);
    b = vec3(c, s + n.y * n.y * a, -n.y);
}

vec3 toFrame(vec3 local, vec3 n) {
    vec3 t, b;
    tangentFrame(n, t, b);
    return local.x * t + local.y * b + local.z * n;
}
