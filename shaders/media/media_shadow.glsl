// The shadow maps' visibility of light i from a point in the medium (SHADOWS): one hard
// comparison (the nearest sampler: the maps are bound with ShadowFilter::Hard) of the map that
// holds view point x (its cascade by view depth, or its cube face or paraboloid), the point
// moved toward the light by the map's constant bias and one texel (a point in the air has no
// surface to bias from, only the map's own depth steps). The maps are fitted to the meshes,
// not to the media: a point outside a map's extent (off its sides, behind its eye) or past its
// far plane has no caster stored between it and the light there, so it counts as lit (a
// reversed-Z depth below 0 would otherwise fail against the cleared 0). 1 for lights without
// maps, or without SHADOWS.
float mediaLightVisibility(int i, vec3 x, vec3 toLight) {
#ifdef SHADOWS
    const int k = int(lights[i].shadowRecord);
    if (k < 0) return 1.0;
    if (shadowHasCone(k) && dot(-toLight, shadowLights[k].spotAxis) < shadowLights[k].spotCosOuter) return 0.0;
    int m = 0;
    for (int c = 0; c + 1 < shadowLights[k].mapCount; ++c) m += -x.z > shadowLights[k].cascades[c].sliceEnd ? 1 : 0;
    if (shadowIsPoint(k)) m = shadowPointMap(k, x);
    const vec3 q = x + toLight * (shadowLights[k].constantBias + shadowTexel(k, x, m));
    const vec4 c = shadowMapCoord(k, q, m);
    const bool outside = !(c.w > 0.0) || any(lessThan(c.xy, vec2(0.0))) || any(greaterThan(c.xy, vec2(1.0)));
    return outside ? 1.0 : texture(shadowMaps, vec4(c.xy, shadowLights[k].cascades[m].layer, max(c.z, 0.0)));
#else
    return 1.0;
#endif
}
