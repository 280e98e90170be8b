// The scene's lights (LightRecords, src/gbuffer/light_records.hpp) and the irradiance each
// gives a view-space point: the G-buffer's lighting and SSDO's lights pass. RECT_LIGHTS
// compiles the rect lights' polygon clipping in. Needs math.glsl and gbuffer_bindings.h.
layout(std430, binding = GBUFFER_LIGHTS_SSBO_BINDING) readonly buffer Lights {
    LightData lights[];
};

#ifdef RECT_LIGHTS
// Compiled in only for scenes with rect lights (llvmpipe runs both sides of a branch under
// a mask). No local arrays: indexed ones cost llvmpipe about 15x the whole pass.

// Lambert's term of the polygon edge a -> b seen from the origin, against normal n.
float rectEdgeTerm(vec3 a, vec3 b, vec3 n) {
    const vec3 ua = safeNormalize(a, vec3(0.0)), ub = safeNormalize(b, vec3(0.0));
    const vec3 c = cross(ua, ub);
    const float s = length(c);
    // atan(|a x b|, a.b) keeps the edge angle accurate for tiny, distant rectangles.
    return s > 0.0 ? atan(s, dot(ua, ub)) * dot(c / s, n) : 0.0;
}

// Adds the part of edge a -> b above the plane dot(x, n) = 0 (Sutherland-Hodgman in one
// step); notes where the outline leaves the hemisphere and where it comes back, between
// which the clipped polygon runs along the plane. Zero vectors add nothing.
void rectClippedEdge(vec3 a, vec3 b, vec3 n, inout float sum, inout vec3 leaves, inout vec3 returns) {
    const float da = dot(a, n), db = dot(b, n);
    const bool aAbove = da >= 0.0, bAbove = db >= 0.0;
    const vec3 x = aAbove == bAbove ? a : a + (b - a) * (da / (da - db));
    if (aAbove || bAbove) sum += rectEdgeTerm(aAbove ? a : x, bAbove ? b : x, n);
    if (aAbove && !bAbove) leaves = x;
    if (!aAbove && bAbove) returns = x;
}

// Projected solid angle of a one-sided rectangle seen from p (normal n): Lambert's formula
// for polygons, after clipping the rectangle to the hemisphere above p. Exact; per unit
// radiance it is the irradiance.
float rectProjectedSolidAngle(vec3 p, vec3 n, LightData light) {
    const vec3 centre = light.position - p;
    if (dot(-centre, light.direction) <= 0.0) return 0.0; // p is behind the emitting side
    const vec3 u = light.halfWidthAxis;
    const vec3 v = normalize(cross(light.direction, u)) * light.halfHeight;
    const vec3 c0 = centre - u - v, c1 = centre + u - v, c2 = centre + u + v, c3 = centre - u + v;
    float sum = 0.0;
    vec3 leaves = vec3(0.0), returns = vec3(0.0);
    rectClippedEdge(c0, c1, n, sum, leaves, returns);
    rectClippedEdge(c1, c2, n, sum, leaves, returns);
    rectClippedEdge(c2, c3, n, sum, leaves, returns);
    rectClippedEdge(c3, c0, n, sum, leaves, returns);
    sum += rectEdgeTerm(leaves, returns, n); // along the plane; 0 when the outline never crosses it
    return 0.5 * abs(sum);
}
#endif

// Irradiance from one light at view-space point p with shading normal ns; lights behind
// the geometric surface (ng) contribute nothing.
vec3 irradiance(LightData light, vec3 p, vec3 ns, vec3 ng) {
    int type = int(light.type);
#ifdef RECT_LIGHTS
    if (type == GBUFFER_LIGHT_RECT) return light.radiance * rectProjectedSolidAngle(p, ns, light);
#endif
    vec3 l;
    float falloff = 1.0;
    if (type == GBUFFER_LIGHT_DIRECTIONAL) {
        l = -light.direction;
    } else {
        vec3 toLight = light.position - p;
        float d2 = dot(toLight, toLight);
        if (!(d2 > 0.0)) return vec3(0.0); // at the light itself the direction is undefined
        l = toLight * inversesqrt(d2);
        float r = light.radius;
        // Bounded by the largest float so that falloff * cos is never Inf * 0 = NaN.
        falloff = min(1.0 / max(d2, r * r), kFloatMax);
        if (type == GBUFFER_LIGHT_SPOT) falloff *= spotCone(dot(-l, light.direction), light.cosInner, light.cosOuter);
        // A Lambertian sphere of radiance L has intensity pi r^2 L in every direction: exact
        // while it is entirely above the horizon, an approximation (cosine at its centre) near it.
        if (type == GBUFFER_LIGHT_SPHERE) falloff *= OBSCURA_PI * r * r;
    }
    if (dot(ng, l) <= 0.0) return vec3(0.0);
    return light.radiance * (falloff * max(dot(ns, l), 0.0));
}
