// Screen-space lookups shared by the AO, SSDO and indirect passes: what the G-buffer holds at a
// pixel, and how big a world-space length looks on screen. The projections read the camera that
// loadPixelToWorld() copied (pixel_to_world.glsl), not the uniforms.
#ifndef SSGI_SCREEN_SPACE_GLSL
#define SSGI_SCREEN_SPACE_GLSL

#include "pixel_to_world.glsl"

// Distance along the camera's view axis.
float viewDepth(vec3 world) { return dot(worldToGbuffer.depthRow, vec4(world, 1.0)); }

// The shortest length the shaders tell from zero: SCENE_TINY of the scene's diagonal. A distance
// or depth a shader divides by is kept at least this long (its square: tinyLength2), never at a
// length in absolute units, which would be most of a scene in nanometres (1e-9 units) and
// nothing in one of 1e9.
float tinyLength() { return SCENE_TINY * frame.sceneDiagonal; }
float tinyLength2() { return tinyLength() * tinyLength(); }

// Pixels covered by one scene unit at the given view depth.
float pixelsPerUnit(float depth) {
    return abs(frame.projection[1][1]) * 0.5 * frame.viewport.y / max(depth, tinyLength());
}

bool insideViewport(vec2 pixel) {
    return all(greaterThanEqual(pixel, vec2(0.0))) &&
           all(lessThan(pixel, worldToGbuffer.viewport));
}

// The camera's right and up axes in world space: the directions of a pixel's step in x and in
// y (down) in the mapping loadPixelToWorld copies, not the view matrix's rows read from the
// frame's uniforms. GTAO reads them inside its slice loop, and uniform reads there make lavapipe
// (Mesa 22.3) compile the AO shader again at every dispatch with the uniforms' values inlined,
// keeping every copy: the process grew with each frame.
vec3 cameraRight() { return normalize(gbufferToWorld.x); }
vec3 cameraUp() { return -normalize(gbufferToWorld.y); }

// World point -> pixel coordinates (x right, y down) and its view depth in z.
vec3 projectToPixel(vec3 world) {
    vec4 clip = worldToGbuffer.viewProjection * vec4(world, 1.0);
    vec2 uv = clip.xy / clip.w * 0.5 + 0.5;
    return vec3(uv * worldToGbuffer.viewport, clip.w);
}

#endif
