// World positions from depths: the G-buffer (gbuffer_position.glsl), last frame's G-buffer
// (temporal.glsl) and the RSM (rsm_vpl.glsl) keep a depth per texel, not a position. A
// texel's position is the ray through its centre taken to that depth along the view axis:
// eye + (x * centre.x + y * centre.y + origin) * depth, the columns of FrameUniforms'
// pixelToWorld, previousPixelToWorld and lightPixelToWorld (renderer.cpp).
// Every shader that includes this calls loadPixelToWorld() first thing in main(): it copies the
// three mappings, and the camera's projection back to pixels, out of the frame's uniforms once,
// since reading the uniforms at each use inside the passes' sample loops is slow on a CPU device
// (docs/frame.md measures it). A shader that does not call it reconstructs every position as the
// origin.
// Needs: frame.
#ifndef SSGI_PIXEL_TO_WORLD_GLSL
#define SSGI_PIXEL_TO_WORLD_GLSL

struct PixelToWorld {
    vec3 x, y, origin, eye;
};
PixelToWorld gbufferToWorld, historyToWorld, rsmToWorld;
vec2 rsmNearFar; // the light's near and far planes (its depth target is not linear)

// And back, world -> this frame's pixels (screen_space.glsl's projectToPixel and viewDepth,
// which the passes call inside their marches and sample loops): copied once for the same reason.
struct WorldToPixel {
    mat4 viewProjection;
    vec4 depthRow; // view depth = dot(depthRow, vec4(world, 1)): minus the view matrix's 3rd row
    vec2 viewport;
};
WorldToPixel worldToGbuffer;

PixelToWorld pixelToWorld(mat4 m) { return PixelToWorld(m[0].xyz, m[1].xyz, m[2].xyz, m[3].xyz); }

void loadPixelToWorld() {
    gbufferToWorld = pixelToWorld(frame.pixelToWorld);
    historyToWorld = pixelToWorld(frame.previousPixelToWorld);
    rsmToWorld = pixelToWorld(frame.lightPixelToWorld);
    rsmNearFar = frame.lightFrustum.xy;
    mat4 view = frame.view;
    worldToGbuffer = WorldToPixel(frame.viewProjection,
                                  -vec4(view[0][2], view[1][2], view[2][2], view[3][2]),
                                  frame.viewport.xy);
}

// The world position at texel `texel` of an image whose view `m` maps, at view depth `depth`.
vec3 worldAt(PixelToWorld m, ivec2 texel, float depth) {
    vec2 centre = vec2(texel) + 0.5;
    return m.eye + (m.x * centre.x + m.y * centre.y + m.origin) * depth;
}

#endif
