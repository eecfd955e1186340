// The RSM's world positions (its virtual point lights' places). The RSM keeps none: its depth
// target, which the shadow pass reads as the shadow map, gives the light-view depth of each
// texel, and the position is the ray through the texel's centre from the light taken to that
// depth (pixel_to_world.glsl). The D32 depth holds the distance to within about 6e-5 of the far
// plane's (its near plane lies at a thousandth of the far).
// Needs: frame, rsmDepth; loadPixelToWorld() called in main().
#ifndef SSGI_RSM_POSITION_GLSL
#define SSGI_RSM_POSITION_GLSL

#include "pixel_to_world.glsl"

// The world position at an RSM texel (w = 1), or vec4(0) where nothing was drawn (depth 1).
vec4 rsmPosition(ivec2 texel) {
    float depth = texelFetch(rsmDepth, texel, 0).r;
    float near = rsmNearFar.x, far = rsmNearFar.y;
    float z = near * far / (far - depth * (far - near)); // along the light's axis
    return depth >= 1.0 ? vec4(0.0) : vec4(worldAt(rsmToWorld, texel, z), 1.0);
}

#endif
