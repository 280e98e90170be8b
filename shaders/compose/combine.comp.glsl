// The combined radiance per pixel (see CombineFormula) and the largest luminance of the frame
// for Drago's tone mapping (positive floats order like their bits). The exposure is the tone
// mapper's: stored after it, a small exposure would push the values into half floats'
// subnormals (below 6.1e-5), whose steps are 6e-8 wide, and lose them before any mapping.
// Background pixels keep their direct radiance only: a host's albedo there need not be 0
// (ours is), and ambient light on the sky would brighten it by rho * L_amb. So do pixels whose
// depth no surface can have (NaN, outside [0, 1], beyond kMaxViewDistance: isBackgroundDepth),
// as in every other pass.
#include "compose_common.glsl"

layout(local_size_x = COMPOSE_WORKGROUP, local_size_y = COMPOSE_WORKGROUP) in;
layout(binding = COMPOSE_DIRECT_UNIT) uniform sampler2D directRadiance;
layout(binding = COMPOSE_ALBEDO_UNIT) uniform sampler2D albedo;
layout(binding = COMPOSE_AO_UNIT) uniform sampler2D aoTexture;
layout(binding = COMPOSE_INDIRECT_UNIT) uniform sampler2D indirect;
layout(binding = COMPOSE_DEPTH_UNIT) uniform sampler2D depth;
layout(binding = COMPOSE_RADIANCE_IMAGE, rgba16f) writeonly uniform image2D radianceOut;
layout(std430, binding = COMPOSE_LUMINANCE_SSBO) buffer Luminance {
    uint maxLuminanceBits;
};

void main() {
    const ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(pixel, compose.size))) return;
    const vec3 direct = clampRadiance(texelFetch(directRadiance, pixel, 0).rgb);
    const bool surface = !isBackgroundDepth(texelFetch(depth, pixel, 0).r, compose.clearDepth, compose.farthestDepth);
    const vec3 rho = surface ? clampAlbedo(texelFetch(albedo, pixel, 0).rgb) : vec3(0.0);
    const float ao = surface && (compose.inputs & COMPOSE_HAS_AO) != 0 ? clamp(texelFetch(aoTexture, pixel, 0).r, 0.0, 1.0) : 1.0;
    const bool hasIndirect = surface && (compose.inputs & COMPOSE_HAS_INDIRECT) != 0;
    const vec3 l1 = hasIndirect ? clampRadiance(texelFetch(indirect, pixel, 0).rgb) : vec3(0.0);
    const vec3 ambient = rho * ao * compose.ambient;
    vec3 l;
    if (compose.formula == COMPOSE_FORMULA_THESIS) l = ambient + compose.indirectScale * l1 + ao * direct;
    else if (compose.formula == COMPOSE_FORMULA_STANDARD) l = direct + ambient + compose.indirectScale * l1;
    else l = direct + (hasIndirect ? compose.indirectScale * l1 : ambient); // indirect light replaces ambient
    const vec3 combined = clampRadiance(l);
    imageStore(radianceOut, pixel, vec4(combined, 1.0));
    // Without its sign bit: max(-0.0, 0.0) may be -0.0, whose bits would beat every positive float.
    atomicMax(maxLuminanceBits, floatBitsToUint(max(luminanceOf(combined), 0.0)) & 0x7FFFFFFFu);
}
