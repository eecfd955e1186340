#version 460
#extension GL_GOOGLE_include_directive : require
// Direct light from the spot light, with a hard shadow test against the reflective shadow map's
// depth: radiance = albedo/pi * I(w) * cos(theta) / d^2 where the light sees the point.
#include "shared.h"
#include "common.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

layout(set = 0, binding = 0, std140) uniform FrameBlock { FrameUniforms frame; };
layout(set = 0, binding = 1) uniform sampler2D gbufferPosition;
layout(set = 0, binding = 2) uniform sampler2D gbufferNormal;
layout(set = 0, binding = 3) uniform sampler2D gbufferAlbedo;
layout(set = 0, binding = 4) uniform sampler2D rsmDepth;
layout(set = 0, binding = 5, rgba16f) uniform writeonly image2D directRadiance;

// 1 where the light's shadow map sees p (or something farther), 0 where an occluder is nearer.
// The lookup point is pushed off the surface along its normal by a couple of shadow-map texels
// (normal-offset bias): a surface the light grazes covers less than a texel of the map, and
// without the push it would shadow itself in a stipple (acne).
float hardShadow(vec3 p, vec3 n) {
    float size = frame.lightFrustum.w;
    float texelAtP = distance(p, frame.lightPosition.xyz) * 2.0 * frame.lightFrustum.z / size;
    vec3 lookup = p + n * (frame.params.y * texelAtP);
    vec4 clip = frame.lightViewProjection * vec4(lookup, 1.0);
    if (clip.w <= 0.0) return 0.0;
    vec2 uv = clip.xy / clip.w * 0.5 + 0.5;
    if (any(lessThan(uv, vec2(0.0))) || any(greaterThan(uv, vec2(1.0)))) return 0.0;
    float occluder = texelFetch(rsmDepth, ivec2(min(uv * size, vec2(size - 1.0))), 0).r;
    float occluderDistance = linearDepth(occluder, frame.lightFrustum.x, frame.lightFrustum.y);
    // Depth bias: one texel's world size at this distance covers the depth quantisation.
    float texelWorld = clip.w * 2.0 * frame.lightFrustum.z / size;
    return clip.w <= occluderDistance + texelWorld ? 1.0 : 0.0;
}

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(pixel, ivec2(frame.viewport.xy)))) return;
    vec4 position = texelFetch(gbufferPosition, pixel, 0);
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
        radiance = albedo / PI * irradiance * hardShadow(p, n);
    }
    imageStore(directRadiance, pixel, vec4(radiance, 1.0));
}
