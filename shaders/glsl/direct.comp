#version 460
#extension GL_GOOGLE_include_directive : require
// Direct light from the spot light: radiance = albedo/pi * I(w) * cos(theta) / d^2, times the
// fraction of the light the shadow pass found unblocked.
#include "shared.h"
#include "common.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

layout(set = 0, binding = 0, std140) uniform FrameBlock { FrameUniforms frame; };
layout(set = 0, binding = 1) uniform sampler2D gbufferViewDepth;
layout(set = 0, binding = 2) uniform sampler2D gbufferNormal;
layout(set = 0, binding = 3) uniform sampler2D gbufferAlbedo;
layout(set = 0, binding = 4) uniform sampler2D shadowImage;
layout(set = 0, binding = 5, rgba16f) uniform writeonly image2D directRadiance;

#include "gbuffer_position.glsl"

void main() {
    loadPixelToWorld(); // pixel_to_world.glsl
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(pixel, ivec2(frame.viewport.xy)))) return;
    vec4 position = gbufferPosition(pixel);
    if (position.w == 0.0) {
        imageStore(directRadiance, pixel, vec4(0.0));
        return;
    }
    vec3 p = position.xyz;
    vec3 n = texelFetch(gbufferNormal, pixel, 0).xyz;
    vec3 albedo = texelFetch(gbufferAlbedo, pixel, 0).rgb;
    vec3 toLight = frame.lightPosition.xyz - p;
    float distance2 = dot(toLight, toLight);
    vec3 l = toLight * inversesqrt(distance2);
    float cosTheta = dot(n, l);
    vec3 radiance = vec3(0.0);
    if (cosTheta > 0.0) {
        float spot = spotAttenuation(-l, frame.lightDirection.xyz, frame.lightDirection.w,
                                     frame.lightColor.w);
        vec3 irradiance = frame.lightColor.rgb * spot * cosTheta / distance2;
        radiance = albedo / PI * irradiance * texelFetch(shadowImage, pixel, 0).r;
    }
    imageStore(directRadiance, pixel, vec4(radiance, 1.0));
}
