#version 460
#extension GL_GOOGLE_include_directive : require
// world.lookup (indirect_method 3): the bounce looked up in the world cache rather than
// gathered (world_lookup.glsl), at every pixel, or with world_half_res at every other pixel in x
// and y (the top-left pixel of each 2x2 block, into world.indirect_half, which world.upsample
// brings to full resolution). With SKY, the sky's visibility the cells hold beside it
// (world_sky_visibility.comp), into world.sky_visibility (or world.sky_visibility_half).
// Background: zero, its alpha 0 too; its sky's visibility 1.
#include "shared.h"
#include "common.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(constant_id = 0) const int SCALE = 1; // 2: a pixel of every 2x2 block (world_half_res)
layout(constant_id = 1) const bool SKY = false; // the cells hold the sky's visibility

layout(set = 0, binding = 0, std140) uniform FrameBlock { FrameUniforms frame; };
layout(set = 0, binding = 1) uniform sampler2D gbufferViewDepth;
layout(set = 0, binding = 2) uniform sampler2D gbufferNormal;
layout(set = 0, binding = 3) uniform usampler2D worldKeys;
layout(set = 0, binding = 4) uniform sampler2D worldIrradiance;
layout(set = 0, binding = 5) uniform usampler2D worldUsed;
layout(set = 0, binding = 6) uniform sampler2D worldPoints;
layout(set = 0, binding = 7) uniform sampler2D worldDirections;
layout(set = 0, binding = 8) uniform sampler2D worldSky;
layout(set = 0, binding = 9, rgba16f) uniform writeonly image2D indirectImage;
layout(set = 0, binding = 10, rgba16f) uniform writeonly image2D skyImage; // unwritten: !SKY
layout(push_constant) uniform WorldBlock { WorldConstants constants; };

#include "gbuffer_position.glsl"
#include "world_cache.glsl"
#include "world_lookup.glsl"

void main() {
    loadPixelToWorld(); // pixel_to_world.glsl
    ivec2 target = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(target, (ivec2(frame.viewport.xy) + SCALE - 1) / SCALE))) return;
    ivec2 pixel = target * SCALE;
    vec4 position = gbufferPosition(pixel);
    if (position.w == 0.0) {
        imageStore(indirectImage, target, vec4(0.0));
        if (SKY) imageStore(skyImage, target, vec4(1.0));
        return;
    }
    vec3 n = texelFetch(gbufferNormal, pixel, 0).xyz;
    vec4 sky;
    imageStore(indirectImage, target, worldLookup(position.xyz, n, constants.work.w, sky));
    if (SKY) imageStore(skyImage, target, sky);
}
