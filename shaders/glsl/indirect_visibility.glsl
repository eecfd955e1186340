// The screen-space visibility test of a VPL (thesis 3.3, equation 8), shared by the indirect
// light's gathers (indirect_gather.glsl, indirect_importance.comp).
// Needs: frame, gbufferViewDepth, gbufferNormal, pixel_to_world.glsl (loadPixelToWorld),
// VISIBILITY_STEPS, constants (IndirectConstants), screen_space.glsl, PEELING and secondLayer
// (depth peeling's layer, peel.position; read only where PEELING is 1), LIGHT_CHECK and
// lightDepthMin (light_depth_min_pass.cpp; read only where LIGHT_CHECK is 1).
#ifndef SSGI_INDIRECT_VISIBILITY_GLSL
#define SSGI_INDIRECT_VISIBILITY_GLSL

// The light check's tolerance, in light_depth_min's texels of depth over the cosine at which the
// light meets the VPL's plane: its nearest depth of a block stands for the block's every texel.
const float LIGHT_CHECK_TOLERANCE = 0.5;

// Whether the light sees x in the open space above the plane (q, nq) of a VPL's lit surface:
// the nearest surface light_depth_min holds around x lies at or beyond that plane (within
// LIGHT_CHECK_TOLERANCE of its texels' depth over the cosine at which the light's ray meets the
// plane), so that nothing stands between the light and the plane there, and x is on the
// light's side of it.
bool lightSeesOpenAbove(vec3 x, vec3 q, vec3 nq) {
    vec4 clip = frame.lightViewProjection * vec4(x, 1.0);
    if (clip.w <= frame.lightFrustum.x) return false;
    vec2 uv = clip.xy / clip.w * 0.5 + 0.5;
    if (any(lessThan(uv, vec2(0.0))) || any(greaterThan(uv, vec2(1.0)))) return false;
    vec3 fromLight = x - frame.lightPosition.xyz;
    float along = dot(fromLight, nq);
    if (along >= 0.0) return false; // the ray meets the plane from behind, or never
    // Depth along the light's axis is linear along its rays: the plane's, through x.
    float planeDepth = clip.w * dot(q - frame.lightPosition.xyz, nq) / along;
    if (clip.w >= planeDepth) return false;
    float size = float(textureSize(lightDepthMin, 0).x);
    float nearest = texelFetch(lightDepthMin, ivec2(min(uv * size, vec2(size - 1.0))), 0).r;
    float texelDepth = planeDepth * 2.0 * frame.lightFrustum.z / size;
    float cosine = -along / length(fromLight);
    return nearest > planeDepth - LIGHT_CHECK_TOLERANCE * texelDepth / max(cosine, 0.2);
}

// Whether the segment p -> q stays in front of what the camera sees (or, with LIGHT_CHECK, where
// the light sees it open); nq is the normal of the VPL's surface at q.
bool vplVisible(vec3 p, vec3 q, vec3 nq) {
    vec3 toVpl = q - p;
    float far = 0.99 * length(toVpl); // the last step stops just short of q's own surface
    // The steps are log-spaced from a fixed fraction of the way, indirect_visibility_start (the
    // same test in any unit): distance_i = near (far / near)^(i / steps), each the last times a
    // constant ratio. The farther the start, the shorter the far steps: a long step lands
    // behind whatever the camera sees there and, by the thickness guess below, takes the open
    // space behind an object for an occluder. From 1% of the way, 6 steps left the Cornell
    // box's bounce 19% too dark (its mean 0.078 against the reference's 0.096); from 10%, 8%
    // (docs/effects.md).
    float start = constants.visibilityStart;
    float ratio = pow(1.0 / start, 1.0 / float(VISIBILITY_STEPS));
    vec3 direction = toVpl / length(toVpl);
    // The projection is linear in homogeneous coordinates, so a point along the segment is
    // p's clip position plus the distance times the direction's: one matrix product a VPL, not
    // one a step.
    vec4 clipP = worldToGbuffer.viewProjection * vec4(p, 1.0);
    vec4 clipDirection = worldToGbuffer.viewProjection * vec4(direction, 0.0);
    float distance = start * far, previous = 0.0;
    for (int i = 1; i <= VISIBILITY_STEPS; ++i) {
        distance *= ratio;
        vec4 clip = clipP + distance * clipDirection;
        float stepLength = distance - previous;
        float stepStart = previous;
        previous = distance;
        if (clip.w <= 0.0) continue;
        vec2 projected = (clip.xy / clip.w * 0.5 + 0.5) * worldToGbuffer.viewport;
        if (!insideViewport(projected)) continue;
        ivec2 pixel = ivec2(projected);
        float depth = texelFetch(gbufferViewDepth, pixel, 0).r; // clip.w is the step's
        if (depth == 0.0) continue;
        // Behind the visible surface (beyond a sliver for the depth of one pixel), by no more
        // than this step can have crossed: the step's length, over the cosine at which the
        // camera sees that surface (a slanted surface's depth changes across the step's
        // pixels; at most doubled, which keeps 97.5% of the wall's leak out and leaves the
        // Cornell box's VPLs seen past the blocks alone). Farther behind, the segment passes
        // behind the object in open space (a thickness guess: without it every VPL seen past a
        // silhouette is lost). The surface's normal and position are read only where the step
        // lies within twice its length behind, the most the cosine can allow.
        float behind = clip.w - depth;
        if (behind <= 0.01 * clip.w) continue;
        // With depth peeling's second layer (the nearest surface behind the visible one: a
        // closed object's far side) no guess is needed: a step between the two layers is
        // inside the object, one beyond the second in the open space behind it (the Cornell
        // box's ceiling and upper back wall, which the guess left at 0.80-0.85 of their bounce,
        // docs/effects.md). Where nothing lies behind, the guess below. A long step can cross
        // a thin wall from one side to the other unseen, which the guess would have caught:
        // Sponza's error rises with it, and depth peeling stays off by default.
        if (PEELING != 0) {
            vec4 back = texelFetch(secondLayer, pixel, 0);
            if (back.w != 0.0) {
                float backDepth = (worldToGbuffer.viewProjection * vec4(back.xyz, 1.0)).w;
                if (clip.w < backDepth) return false;
                continue;
            }
        }
        if (behind >= 2.0 * stepLength) continue;
        vec3 surfaceNormal = texelFetch(gbufferNormal, pixel, 0).xyz;
        vec3 surface = worldAt(gbufferToWorld, pixel, depth);
        float facing = abs(dot(surfaceNormal, normalize(gbufferToWorld.eye - surface)));
        if (behind >= stepLength / max(facing, 0.5)) continue;
        // Taken for blocked. At the last step the light can tell better, where it sees the
        // step's stretch of the segment (by default from two thirds of the way) open above the
        // VPL's surface, asked at the stretch's middle. The Cornell box's upper back wall takes
        // its brightest light from the blocks' tops, which the camera below them does not see:
        // the last steps just above a top project onto the block's front face, behind it by
        // less than the guess's thickness, and the wall was left at 0.76-0.88 of the reference
        // (docs/effects.md). Asked at the step's own point (the stretch's end) instead, the
        // Cornell box's one frame was 0.00702 against 0.00682: a stretch that crosses an object
        // the camera sees in front is caught by the guess at a point past it in the open. Asked
        // at both, 0.00677 (Sponza 0.00850 against 0.00856), for 17 ms more of Sponza's 80 ms
        // gather on lavapipe. The earlier steps' checks changed no scene by more than 0.1%.
        if (LIGHT_CHECK == 0 || i < VISIBILITY_STEPS) return false;
        return lightSeesOpenAbove(p + mix(stepStart, distance, 0.5) * direction, q, nq);
    }
    return true;
}

#endif
