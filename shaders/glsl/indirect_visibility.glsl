// The screen-space visibility test of a VPL (thesis 3.3, equation 8), shared by the indirect
// light's gathers (indirect_gather.glsl, indirect_importance.comp).
// Needs: frame, gbuffer_position.glsl, gbufferNormal, VISIBILITY_STEPS, screen_space.glsl.
#ifndef SSGI_INDIRECT_VISIBILITY_GLSL
#define SSGI_INDIRECT_VISIBILITY_GLSL

// Whether the segment p -> q stays in front of what the camera sees.
bool vplVisible(vec3 p, vec3 q) {
    vec3 toVpl = q - p;
    float far = 0.99 * length(toVpl); // the last step stops just short of q's own surface
    float near = 0.01 * far; // a fixed fraction: the same test in any unit
    vec3 direction = toVpl / length(toVpl);
    float previous = 0.0;
    for (int i = 1; i <= VISIBILITY_STEPS; ++i) {
        float distance = near * pow(far / near, float(i) / float(VISIBILITY_STEPS));
        vec3 projected = projectToPixel(p + direction * distance);
        float stepLength = distance - previous;
        previous = distance;
        if (projected.z <= 0.0 || !insideViewport(projected.xy)) continue;
        vec4 stored = gbufferPosition(ivec2(projected.xy));
        if (stored.w == 0.0) continue;
        // Behind the visible surface (beyond a sliver for the depth of one pixel), by no more
        // than this step can have crossed: the step's length, over the cosine at which the
        // camera sees that surface (a slanted surface's depth changes across the step's
        // pixels; at most doubled, which keeps 97.5% of the wall's leak out and leaves the
        // Cornell box's VPLs seen past the blocks alone). Farther behind, the segment passes
        // behind the object in open space (a thickness guess: without it every VPL seen past a
        // silhouette is lost). The normal is fetched only where the step lies within twice its
        // length behind, the most the cosine can allow.
        float behind = projected.z - viewDepth(stored.xyz);
        if (behind <= 0.01 * projected.z || behind >= 2.0 * stepLength) continue;
        vec3 surfaceNormal = texelFetch(gbufferNormal, ivec2(projected.xy), 0).xyz;
        float facing = abs(dot(surfaceNormal, normalize(gbufferToWorld.eye - stored.xyz)));
        if (behind < stepLength / max(facing, 0.5)) return false;
    }
    return true;
}

#endif
