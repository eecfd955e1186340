#version 460
#extension GL_GOOGLE_include_directive : require
// The light's depth in blocks of BLOCK x BLOCK RSM texels: each block's nearest surface, as a
// distance along the light's axis (light_depth_min_pass.cpp). Depth is monotonic in that
// distance, so the nearest depth is the nearest distance.
#include "shared.h"
#include "common.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(constant_id = 0) const int BLOCK = 4;

layout(set = 0, binding = 0, std140) uniform FrameBlock { FrameUniforms frame; };
layout(set = 0, binding = 1) uniform sampler2D rsmDepth;
layout(set = 0, binding = 2, r32f) uniform writeonly image2D nearestDepth;

void main() {
    ivec2 texel = ivec2(gl_GlobalInvocationID.xy);
    ivec2 side = imageSize(nearestDepth);
    if (any(greaterThanEqual(texel, side))) return;
    ivec2 mapSide = textureSize(rsmDepth, 0);
    float nearest = 1.0; // the far plane
    for (int y = 0; y < BLOCK; ++y)
        for (int x = 0; x < BLOCK; ++x) {
            ivec2 source = min(texel * BLOCK + ivec2(x, y), mapSide - 1);
            nearest = min(nearest, texelFetch(rsmDepth, source, 0).r);
        }
    imageStore(nearestDepth, texel,
               vec4(linearDepth(nearest, frame.lightFrustum.x, frame.lightFrustum.y)));
}
