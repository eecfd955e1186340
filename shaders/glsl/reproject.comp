#version 460
#extension GL_GOOGLE_include_directive : require
// The reverse reprojection every cached effect shares (thesis 3.1.1): for each pixel, where its
// surface lay in last frame's image and which history texels hold it (reprojection.glsl),
// computed once a frame instead of once in every effect's pass and again in its temporal pass.
// Each effect adds what is its own (temporal.glsl reproject).
#include "shared.h"

layout(local_size_x = 8, local_size_y = 8) in;

layout(set = 0, binding = 0, std140) uniform FrameBlock { FrameUniforms frame; };
layout(set = 0, binding = 1) uniform sampler2D gbufferViewDepth;
layout(set = 0, binding = 2) uniform sampler2D gbufferNormal;
layout(set = 0, binding = 3) uniform sampler2D historyViewDepth;
layout(set = 0, binding = 4, r32ui) uniform writeonly uimage2D reprojectionImage;
layout(push_constant) uniform ReprojectionBlock { ReprojectionConstants constants; };

#include "gbuffer_position.glsl"
#include "screen_space.glsl"
#include "reprojection.glsl"

void main() {
    loadPixelToWorld(); // pixel_to_world.glsl
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(pixel, ivec2(frame.viewport.xy)))) return;
    vec4 position = gbufferPosition(pixel);
    SurfaceReprojection s = SurfaceReprojection(false, vec2(0.0), ivec2(0), 0);
    if (position.w != 0.0 && constants.historyValid != 0)
        s = reprojectSurface(position.xyz, texelFetch(gbufferNormal, pixel, 0).xyz,
                             constants.epsilon, constants.thinGeometry != 0);
    imageStore(reprojectionImage, pixel, uvec4(packReprojection(s), 0u, 0u, 0u));
}
