// The AO parameter block and what every AO pass shares.
#include "ao_bindings.h"

layout(std140, binding = AO_PARAMS_UBO_BINDING) uniform AoBlock {
    AoParams ao;
};

bool aoCosine() { return (ao.flags & AO_FLAG_COSINE) != 0; }
bool aoBent() { return (ao.flags & AO_FLAG_BENT) != 0; }
bool aoGuide() { return (ao.flags & AO_FLAG_GUIDE) != 0; }
ivec2 aoSize() { return ao.size; }
int aoScale() { return ao.scale; }

// Obscurance's rho(d / r) for a hit at distance d (see ObscuranceFalloff); AO: 0.
float aoHitValue(float d) {
    const float t = clamp(d / ao.radius, 0.0, 1.0);
    switch (ao.falloff) {
    case AO_FALLOFF_LINEAR: return t;
    case AO_FALLOFF_QUADRATIC: return t * t;
    case AO_FALLOFF_SMOOTH: return t * t * (3.0 - 2.0 * t);
    default: return 0.0;
    }
}
