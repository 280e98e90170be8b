// The shadow maps' visibility of light i from a point in the medium (SHADOWS): one hard
// comparison of the map that holds view point x (its cascade by view depth, or its cube face
// or paraboloid), the point moved toward the light by the map's constant bias and one texel
// (a point in the air has no surface to bias from, only the map's own depth steps). 1 for
// lights without maps, or without SHADOWS.
float mediaLightVisibility(int i, vec3 x, vec3 toLight) {
#ifdef SHADOWS
    const int k = int(lights[i].shadowRecord);
    if (k < 0) return 1.0;
    if (shadowHasCone(k) && dot(-toLight, shadowLights[k].spotAxis) < shadowLights[k].spotCosOuter) return 0.0;
    int m = 0;
    for (int c = 0; c + 1 < shadowLights[k].mapCount; ++c) m += -x.z > shadowLights[k].cascades[c].sliceEnd ? 1 : 0;
    if (shadowIsPoint(k)) m = shadowPointMap(k, x);
    const vec3 q = x + toLight * (shadowLights[k].constantBias + shadowTexel(k, x, m));
    return shadowLookup(k, q, toLight, m);
#else
    return 1.0;
#endif
}
