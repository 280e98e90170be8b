// Shared by the media passes: the media and lights, the view ray of a pixel, optical depths
// along segments, phase functions, and the guarded forms of the integrals' small pieces.
// Needs depth.glsl, gbuffer_bindings.h and light_irradiance.glsl's light records first.
#include "media_bindings.h"

layout(std140, binding = MEDIA_PARAMS_UBO_BINDING) uniform MediaBlock {
    MediaParams media;
};

layout(binding = MEDIA_GRID_UNIT) uniform sampler3D densityGrid;

// (1 - exp(-x)) / x for x >= 0, the mean transmittance over a step of optical depth x:
// its Taylor series below 1/8 (1 - x/2 + x^2/6 - x^3/24, error < x^4/120 < 2.1e-6 relative),
// where 1 - exp(-x) would cancel; no epsilon.
float oneMinusExpOverX(float x) {
    if (abs(x) < 0.125) return 1.0 - x * (0.5 - x * (1.0 / 6.0 - x * (1.0 / 24.0)));
    return (1.0 - exp(-x)) / x;
}
vec3 oneMinusExpOverX(vec3 x) { return vec3(oneMinusExpOverX(x.x), oneMinusExpOverX(x.y), oneMinusExpOverX(x.z)); }

// The phase function for the cosine between the light's travel direction and the direction
// toward the camera (PhaseFunction in scene.hpp; `g` is Schlick's k for MEDIA_PHASE_SCHLICK).
float mediaPhase(int kind, float g, float c) {
    const float inv4Pi = 1.0 / (4.0 * OBSCURA_PI);
    if (kind == MEDIA_PHASE_RAYLEIGH) return 3.0 / (16.0 * OBSCURA_PI) * (1.0 + c * c);
    if (kind == MEDIA_PHASE_HG) {
        // 1 + g^2 - 2 g c = (1 - g)^2 + 2 g (1 - c): no cancellation where g and c near 1.
        const float d = (1.0 - g) * (1.0 - g) + 2.0 * g * (1.0 - c);
        return inv4Pi * (1.0 - g * g) / (d * sqrt(d));
    }
    if (kind == MEDIA_PHASE_SCHLICK) {
        const float d = (1.0 - g) + g * (1.0 - c);
        return inv4Pi * (1.0 - g * g) / (d * d);
    }
    return inv4Pi;
}

// The parametric interval of world ray o + t w inside medium m's box, clipped to [0, tEnd];
// empty (t0 >= t1) when it misses. Axes the ray runs along (w.a = 0) take the slab test on o.
vec2 mediaBoxInterval(int m, vec3 o, vec3 w, float tEnd) {
    const vec3 lo = media.media[m].boxMin, hi = media.media[m].boxMax;
    float t0 = 0.0, t1 = tEnd;
    for (int a = 0; a < 3; ++a) {
        if (w[a] == 0.0) {
            if (o[a] < lo[a] || o[a] > hi[a]) t1 = -1.0;
            continue;
        }
        float ta = (lo[a] - o[a]) / w[a], tb = (hi[a] - o[a]) / w[a];
        t0 = max(t0, min(ta, tb));
        t1 = min(t1, max(ta, tb));
    }
    return vec2(t0, t1);
}

// Medium m's density at world point x inside its box (MediumDensity): 1, exp(-k (y - y0)),
// or the grid, trilinear (the sampler's weights).
float mediaDensityAt(int m, vec3 x) {
    const int kind = int(media.media[m].density);
    if (kind == MEDIA_DENSITY_HEIGHT) return exp(-media.media[m].heightFalloff * max(x.y - media.media[m].boxMin.y, 0.0));
    if (kind == MEDIA_DENSITY_GRID) {
        const vec3 extent = media.media[m].boxMax - media.media[m].boxMin;
        return texture(densityGrid, clamp((x - media.media[m].boxMin) / max(extent, vec3(1e-30)), 0.0, 1.0)).r;
    }
    return 1.0;
}

bool mediaHolds(int m, vec3 x) {
    return all(greaterThanEqual(x, media.media[m].boxMin)) && all(lessThanEqual(x, media.media[m].boxMax));
}

// Integral of medium m's density over [t.x, t.y] of world ray o + s w (inside its box):
// exact for Constant and Height (the exponential's value at the segment's lower end times the
// mean of exp over its rise, no overflow whichever way the ray climbs), `densitySteps`
// midpoint samples for a grid.
float mediaDensityIntegral(int m, vec3 o, vec3 w, vec2 t) {
    const float length = t.y - t.x;
    const int kind = int(media.media[m].density);
    if (kind == MEDIA_DENSITY_HEIGHT) {
        const float k = media.media[m].heightFalloff, y0 = media.media[m].boxMin.y;
        const float ya = o.y + t.x * w.y - y0, yb = o.y + t.y * w.y - y0;
        return exp(-k * max(min(ya, yb), 0.0)) * length * oneMinusExpOverX(k * abs(yb - ya));
    }
    if (kind == MEDIA_DENSITY_GRID) {
        const float dt = length / float(media.densitySteps);
        float sum = 0.0;
        for (int i = 0; i < media.densitySteps; ++i) sum += mediaDensityAt(m, o + (t.x + (float(i) + 0.5) * dt) * w);
        return sum * dt;
    }
    return length;
}

// Optical depth per channel of the world segment from o toward unit w over `length`
// (kFloatMax: to infinity), through every medium.
vec3 mediaOpticalDepth(vec3 o, vec3 w, float length) {
    vec3 tau = vec3(0.0);
    for (int m = 0; m < media.mediumCount; ++m) {
        const vec2 t = mediaBoxInterval(m, o, w, length);
        if (t.y > t.x) tau += media.media[m].extinction * mediaDensityIntegral(m, o, w, t);
    }
    return tau;
}

// sigma_s (rgb) and sigma_t summed over the media whose box holds world point x.
void mediaCoefficientsAt(vec3 x, out vec3 scattering, out vec3 extinction) {
    scattering = vec3(0.0);
    extinction = vec3(0.0);
    for (int m = 0; m < media.mediumCount; ++m) {
        if (!mediaHolds(m, x)) continue;
        const float density = mediaDensityAt(m, x);
        scattering += media.media[m].scattering * density;
        extinction += media.media[m].extinction * density;
    }
}

// sigma_s p(c) summed over the media holding world point x, per channel.
vec3 mediaScatteringPhase(vec3 x, float c) {
    vec3 s = vec3(0.0);
    for (int m = 0; m < media.mediumCount; ++m) {
        if (mediaHolds(m, x))
            s += media.media[m].scattering * (mediaDensityAt(m, x) * mediaPhase(int(media.media[m].phase), media.media[m].g, c));
    }
    return s;
}

// The view ray of a pixel, in view space: origin, unit direction and the distance to its
// surface (kFloatMax on background pixels).
struct MediaRay {
    vec3 origin;
    vec3 direction;
    float end;
};

MediaRay mediaViewRay(ivec2 pixel, float depth) {
    const vec2 uv = pixelCenterUv(pixel);
    MediaRay r;
    if (isBackground(depth)) {
        // Any depth in front of the camera gives the ray; 0.5 lies between the planes in
        // every convention (standard, reversed, infinite far).
        const vec3 q = viewPositionFromDepth(uv, 0.5);
        r.origin = isPerspective() ? vec3(0.0) : vec3(q.xy, 0.0);
        r.direction = isPerspective() ? safeNormalize(q, vec3(0.0, 0.0, -1.0)) : vec3(0.0, 0.0, -1.0);
        r.end = kFloatMax; // past every box
        return r;
    }
    const vec3 p = viewPositionFromDepth(uv, depth);
    r.origin = isPerspective() ? vec3(0.0) : vec3(p.xy, 0.0);
    r.direction = -viewDirectionTo(p);
    r.end = isPerspective() ? length(p) : -p.z;
    return r;
}

// The light view point x receives from light i, unshadowed and unattenuated: its irradiance
// on a plane facing it (I / max(d^2, r^2) times a spot's cone; a directional light's E),
// W/m^2; the unit direction toward it and its distance (kFloatMax: directional). Point, spot
// and directional lights; area lights give 0, as in the reference's SingleScattering.
vec3 mediaLightAt(int i, vec3 x, out vec3 toLight, out float distance) {
    const LightData light = lights[i];
    const int type = int(light.type);
    toLight = vec3(0.0, 0.0, 1.0);
    distance = 0.0;
    if (type == GBUFFER_LIGHT_DIRECTIONAL) {
        toLight = -light.direction;
        distance = kFloatMax; // past every box
        return light.radiance;
    }
    if (type != GBUFFER_LIGHT_POINT && type != GBUFFER_LIGHT_SPOT) return vec3(0.0);
    const vec3 d = light.position - x;
    const float d2 = dot(d, d);
    if (!(d2 > 0.0)) return vec3(0.0); // at the light itself the direction is undefined
    distance = sqrt(d2);
    toLight = d / distance;
    float falloff = min(1.0 / max(d2, light.radius * light.radius), kFloatMax);
    if (type == GBUFFER_LIGHT_SPOT) falloff *= spotCone(dot(-toLight, light.direction), light.cosInner, light.cosOuter);
    return light.radiance * falloff;
}

vec3 mediaToWorld(vec3 viewPoint) { return (media.viewToWorld * vec4(viewPoint, 1.0)).xyz; }
vec3 mediaDirectionToWorld(vec3 viewDirection) { return mat3(media.viewToWorld) * viewDirection; }

// Optical depth stored in a half float: finite (65504 means "opaque": exp(-65504) is 0 in
// any precision), NaN as opaque.
vec4 mediaStoredDepth(vec3 tau) {
    tau = mix(tau, vec3(kHalfMax), isnan(tau));
    return roundedToHalf(vec4(clamp(tau, vec3(0.0), vec3(kHalfMax)), 1.0));
}

// The part of world ray o + t w, t in [0, end], inside any medium: (first entry, last exit);
// empty (x >= y) when it meets none.
vec2 mediaSpan(vec3 o, vec3 w, float end) {
    vec2 span = vec2(kFloatMax, -kFloatMax);
    for (int m = 0; m < media.mediumCount; ++m) {
        const vec2 t = mediaBoxInterval(m, o, w, end);
        if (t.y > t.x) span = vec2(min(span.x, t.x), max(span.y, t.y));
    }
    return span;
}
