#version 460
#extension GL_GOOGLE_include_directive : require
// Sky visibility beyond the screen, at each pixel (sky_visibility.glsl: how much of the sky's
// light reaches a surface point past the occluders screen-space AO cannot see), which the
// composite multiplies into the closed-form sky term (common.glsl). A property of the surface
// point computed without noise, it is cached as an exact effect: a pixel whose history
// reprojects (and has not blurred past its budget) is skipped (temporal.glsl). With the world
// cache (indirect_method 3, world_sky_visibility) the cells hold it instead
// (world_sky_visibility.comp) and this pass is not made.
#include "shared.h"
#include "common.glsl"
#include "sky_maps.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

layout(set = 0, binding = 0, std140) uniform FrameBlock { FrameUniforms frame; };
layout(set = 0, binding = 1) uniform sampler2D gbufferViewDepth;
layout(set = 0, binding = 2) uniform sampler2D gbufferNormal;
layout(set = 0, binding = 3) uniform sampler2D skyMaps; // depth atlas
layout(set = 0, binding = 4) uniform sampler2D historyViewDepth;
layout(set = 0, binding = 5) uniform usampler2D reprojection;
layout(set = 0, binding = 6) uniform sampler2D historyCount;
layout(set = 0, binding = 7, rgba16f) uniform writeonly image2D sky_visibilityImage;
layout(set = 0, binding = 8, std140) uniform TrianglesBlock { SkyTriangles exact; };
layout(push_constant) uniform VisibilityBlock { SkyVisibilityConstants constants; };

#include "gbuffer_position.glsl"
#include "screen_space.glsl"
#include "temporal.glsl"
#include "sky_visibility.glsl"

void main() {
    loadPixelToWorld(); // pixel_to_world.glsl
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(pixel, ivec2(frame.viewport.xy)))) return;
    vec4 position = gbufferPosition(pixel);
    if (position.w == 0.0) {
        imageStore(sky_visibilityImage, pixel, vec4(1.0));
        return;
    }
    if (converged(pixel, position.xyz, constants.cache)) {
        imageStore(sky_visibilityImage, pixel, SKIPPED); // its cache holds the value
        return;
    }
    vec3 n = normalize(texelFetch(gbufferNormal, pixel, 0).xyz);
    vec3 visibility = skyVisibilityAt(position.xyz, n, constants.maps, constants.aoReach,
                                      constants.normalOffset);
    imageStore(sky_visibilityImage, pixel, vec4(visibility, 1.0));
}
