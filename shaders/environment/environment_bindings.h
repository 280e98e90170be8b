// HDR environments on the GPU: binding points and the lookup block, shared by
// src/environment/*.cpp and shaders/environment/*.glsl (and every module that reads an
// environment through environment.glsl).
#ifndef OBSCURA_ENVIRONMENT_BINDINGS_H
#define OBSCURA_ENVIRONMENT_BINDINGS_H

#include "../common/bindings_preamble.h"

OBSCURA_SHADER_BEGIN

#define ENV_PARAMS_UBO_BINDING 7
#define ENV_CUBE_UNIT 13        // samplerCube: radiance, with mips
#define ENV_IRRADIANCE_UNIT 14  // samplerCube: irradiance by direct convolution, W/m^2
#define ENV_SOURCE_UNIT 0       // the equirectangular source with mips, while the cube is built
#define ENV_CUBE_OUT_IMAGE 0    // the cube's level 0, layered
#define ENV_WORKGROUP 8

// What a lookup needs. Directions are turned into the environment's own frame by
// `rotation` about +y (as Scene::environment's), and radiance is scaled by `intensity`:
// neither changes the precomputed data.
struct EnvironmentParams {
    // Irradiance, the SH projection's 9 coefficients (rgb), each already multiplied by its
    // band's convolution factor A_l, its window factor and its basis constant, so that
    // E(n) = sh[0] + sh[1] x + sh[2] y + sh[3] z + sh[4] xy + sh[5] yz + sh[6] xz
    //        + sh[7] (3y^2 - 1) + sh[8] (x^2 - z^2), n = (x, y, z) in the environment's frame.
    vec4 sh[9];
    float intensity;   // radiance scale, [0, inf)
    float rotationCos; // of the rotation about +y
    float rotationSin;
    float cubeSize;    // texels along a cube face's edge at level 0
    float cubeLevels;  // mip levels of the cube
    float pad0;
    float pad1;
    float pad2;
};

#ifdef __cplusplus
static_assert(sizeof(EnvironmentParams) == 9 * 16 + 2 * 16, "EnvironmentParams must match std140");
#endif

OBSCURA_SHADER_END

#endif
