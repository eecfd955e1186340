// The G-buffer's world positions. The G-buffer stores a view depth per pixel (R32F, 0 where no
// geometry was drawn), not a position: four bytes a pixel rather than sixteen, and last frame's
// depth is the whole position history every cache reprojects against (temporal.glsl). The
// position is the ray through the pixel's centre taken to that depth (FrameUniforms.pixelToWorld),
// the same point the rasteriser interpolated there to within float rounding.
// Needs: frame, gbufferViewDepth.
#ifndef SSGI_GBUFFER_POSITION_GLSL
#define SSGI_GBUFFER_POSITION_GLSL

// The world position at a pixel (w = 1), or vec4(0) where no geometry was drawn.
vec4 gbufferPosition(ivec2 pixel) {
    float depth = texelFetch(gbufferViewDepth, pixel, 0).r;
    if (depth == 0.0) return vec4(0.0);
    return vec4((frame.pixelToWorld * vec4(vec3(vec2(pixel) + 0.5, 1.0) * depth, 1.0)).xyz, 1.0);
}

#endif
