#pragma once
// AO's or indirect light's settings (the fields they share by name) for a small test run.
#include "obscura/ambient_occlusion.hpp"

namespace obscura::test {

template <class Settings>
Settings integratorSettings(float radius, int rays, int steps, AoResolution resolution = AoResolution::Full,
                            int blurTaps = 0) {
    return {.radius = radius, .rays = rays, .steps = steps, .resolution = resolution, .blurRadius = blurTaps};
}

} // namespace obscura::test
