// The G-buffer's world positions. The G-buffer stores a view depth per pixel (R32F, 0 where no
// geometry was drawn), not a position: four bytes a pixel rather than sixteen, and last frame's
// depth is the whole position history every cache reprojects against (temporal.glsl). The
// position is the ray through the pixel's centre taken to that depth (pixel_to_world.glsl), the
// point the rasteriser interpolated there to within float rounding.
// Needs: frame, gbufferViewDepth; loadPixelToWorld() called in main().
#ifndef SSGI_GBUFFER_POSITION_GLSL
#define SSGI_GBUFFER_POSITION_GLSL

#include "pixel_to_world.glsl"

// The world position at a pixel (w = 1), or vec4(0) where no geometry was drawn.
vec4 gbufferPosition(ivec2 pixel) {
    float depth = texelFetch(gbufferViewDepth, pixel, 0).r;
    return depth == 0.0 ? vec4(0.0) : vec4(worldAt(gbufferToWorld, pixel, depth), 1.0);
}

#endif
