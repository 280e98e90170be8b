// Lookups into an environment (EnvironmentMap): radiance from the cube map, irradiance from
// the SH projection or the convolved cube. Directions are world-space; the module binds the
// block and both cubes (EnvironmentBinding::bind).
#include "environment_bindings.h"

layout(std140, binding = ENV_PARAMS_UBO_BINDING) uniform EnvironmentBlock {
    EnvironmentParams environment;
};
layout(binding = ENV_CUBE_UNIT) uniform samplerCube environmentCube;
layout(binding = ENV_IRRADIANCE_UNIT) uniform samplerCube environmentIrradianceCube;

// A world direction in the environment's own frame: its azimuth atan2(x, -z) less the
// rotation (src/reference/environment.cpp's toUv).
vec3 environmentLocal(vec3 w) {
    const float c = environment.rotationCos, s = environment.rotationSin;
    return vec3(w.x * c + w.z * s, w.y, w.z * c - w.x * s);
}

// The cube's level whose texels subtend about `solidAngle` (sr): a lookup that stands for
// that much of the sphere (one of N samples) reads the environment prefiltered to it.
float environmentLevelFor(float solidAngle) {
    const float texel = 4.0 * OBSCURA_PI / (6.0 * environment.cubeSize * environment.cubeSize);
    return clamp(0.5 * log2(max(solidAngle / texel, 1.0)), 0.0, environment.cubeLevels - 1.0);
}

vec3 environmentRadiance(vec3 w, float level) {
    return environment.intensity * textureLod(environmentCube, environmentLocal(w), level).rgb;
}

// Irradiance on a surface of unit normal n from the SH projection (clamped at 0: the order-2
// projection may ring below it opposite a bright source, docs/environment.md).
vec3 environmentIrradianceSh(vec3 n) {
    const vec3 l = environmentLocal(n);
    const vec3 e = environment.sh[0].rgb + environment.sh[1].rgb * l.x + environment.sh[2].rgb * l.y +
                   environment.sh[3].rgb * l.z + environment.sh[4].rgb * (l.x * l.y) +
                   environment.sh[5].rgb * (l.y * l.z) + environment.sh[6].rgb * (l.x * l.z) +
                   environment.sh[7].rgb * (3.0 * l.y * l.y - 1.0) + environment.sh[8].rgb * (l.x * l.x - l.z * l.z);
    return environment.intensity * max(e, vec3(0.0));
}

// Irradiance from the convolved cube.
vec3 environmentIrradiance(vec3 n) {
    return environment.intensity * textureLod(environmentIrradianceCube, environmentLocal(n), 0.0).rgb;
}
