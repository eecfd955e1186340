// Crytek's SSAO (Mittring 2007): points spread through a sphere of the AO radius around p are
// projected into the image; a point lying behind the depth stored there (by less than the
// radius) is occluded. Depth only, no normal: a flat, open surface has half its sphere below
// it and comes out at 0.5 — the grey-flat-surfaces artifact the thesis shows (Fig. 2.1b), kept
// here as the method has it.
float crytekAo(vec3 p, vec3 n, float radius, float rotation) {
    const int count = DIRECTIONS * STEPS;
    int open = 0, counted = 0;
    for (int i = 0; i < count; ++i) {
        // A spherical Fibonacci point at a radius growing with the cube root (uniform in volume).
        float z = 1.0 - 2.0 * (float(i) + 0.5) / float(count);
        float ring = sqrt(max(1.0 - z * z, 0.0));
        float phi = float(i) * 2.39996323 + rotation;
        vec3 offset = vec3(ring * cos(phi), z, ring * sin(phi));
        offset *= radius * pow((float(i) + 0.5) / float(count), 1.0 / 3.0);
        vec3 projected = projectToPixel(p + offset);
        if (projected.z <= 0.0 || !insideViewport(projected.xy)) continue;
        vec4 stored = positionAt(projected.xy);
        ++counted;
        float storedDepth = stored.w == 0.0 ? 1e30 : viewDepth(stored.xyz);
        float behind = projected.z - storedDepth;
        bool occluded = behind > 0.0 && behind < radius;
        open += occluded ? 0 : 1;
    }
    return counted == 0 ? 1.0 : float(open) / float(counted);
}
