// The thesis's AO (3.2): AO(p, n) = 1/k sum max(n . (q_i - p), 0) / D(d_i) (6), with
// D(d) = 1 + a d + b d^2 (7), over k = DIRECTIONS x STEPS G-buffer points q_i taken along
// regular screen directions (turned per pixel and per frame) at log-spaced distances
// S_i = near (far/near)^(i/m) (8). Lengths are measured in AO radii so one (a, b) serves every
// scene scale, and (q - p) is normalised so that a samplePixel's weight is the cosine of its
// direction: a fully occluding samplePixel contributes 1. Returns 1 - occlusion.
float thesisAo(vec2 center, vec3 p, vec3 n, float radius, float radiusPixels, float rotation) {
    float far = radiusPixels;
    float near = min(1.0, far);
    // A single frame samples each step's far end, as (8) does; accumulated frames cover it.
    float stratum = radialOffset(constants.radialOffset, 1.0);
    float occlusion = 0.0;
    for (int d = 0; d < DIRECTIONS; ++d) {
        float angle = rotation + 2.0 * PI * float(d) / float(DIRECTIONS);
        vec2 direction = vec2(cos(angle), sin(angle));
        for (int i = 1; i <= STEPS; ++i) {
            float distance = near * pow(far / near, (float(i) - 1.0 + stratum) / float(STEPS));
            vec2 samplePixel = center + direction * distance;
            if (!insideViewport(samplePixel)) continue;
            vec4 q = positionAt(samplePixel);
            if (q.w == 0.0) continue;
            vec3 toSample = q.xyz - p;
            float d = length(toSample) / radius;
            if (d > 1.0 || d < 1e-5) continue;
            float falloff = 1.0 + constants.falloffA * d + constants.falloffB * d * d;
            occlusion += max(dot(n, toSample) / (d * radius), 0.0) / falloff;
        }
    }
    return 1.0 - occlusion / float(DIRECTIONS * STEPS);
}
