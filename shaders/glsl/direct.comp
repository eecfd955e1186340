#version 460
#extension GL_GOOGLE_include_directive : require
// Direct light from the spot light: radiance = albedo/pi * E, E the light's unoccluded
// irradiance (spotIrradiance: its disk's), times the fraction of the light the shadow pass
// found unblocked.
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

// Points of the light's disk at which spotIrradiance evaluates it.
const int DISK_POINTS = 16;

// Irradiance at p (normal n) from the spot light, unoccluded. A light of radius 0 is a point:
// I(w) cos(theta) / d^2. A light of radius r > 0 is the disk the reference renders (a disk at
// the light's position facing along its axis, docs/ground-truth.md), whose irradiance is that
// formula averaged over the disk's points: DISK_POINTS of them spread evenly over its area
// (r sqrt((j + 1/2) / (N/4)) from the centre, mirrored into the four quadrants). Where the
// light is near p's tangent plane, or near p, the point formula is far off: the Cornell box's
// tall block faces the light edge on, and the point lit its front 40% too dark.
vec3 spotIrradiance(vec3 p, vec3 n) {
    float radius = frame.lightPosition.w;
    vec3 axis = frame.lightDirection.xyz;
    vec3 t = normalize(cross(abs(axis.y) < 0.99 ? vec3(0.0, 1.0, 0.0) : vec3(1.0, 0.0, 0.0), axis));
    vec3 b = cross(axis, t);
    int points = radius > 0.0 ? DISK_POINTS : 1;
    float sum = 0.0;
    for (int i = 0; i < points; ++i) {
        // A quarter of the points stratified over a quadrant (area and angle, a Latin
        // square), mirrored into the other three: a scene symmetric about the light's axis is
        // lit symmetrically.
        int quarter = max(points / 4, 1), j = i % quarter, mirror = i / quarter;
        float angle = 1.57079633 * (float((j * 3) % quarter) + 0.5) / float(quarter);
        float r = points == 1 ? 0.0 : sqrt((float(j) + 0.5) / float(quarter));
        vec2 d = r * vec2(cos(angle), sin(angle));
        if ((mirror & 1) != 0) d.x = -d.x;
        if ((mirror & 2) != 0) d.y = -d.y;
        vec3 toLight = frame.lightPosition.xyz + radius * (d.x * t + d.y * b) - p;
        float distance2 = dot(toLight, toLight);
        vec3 l = toLight * inversesqrt(distance2);
        float cosTheta = dot(n, l);
        if (cosTheta <= 0.0) continue;
        // The cone is narrower than 90 degrees, so this also makes the disk one-sided.
        float spot = spotAttenuation(-l, axis, frame.lightDirection.w, frame.lightColor.w);
        sum += spot * cosTheta / distance2;
    }
    return frame.lightColor.rgb * (sum / float(points));
}

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
    vec3 radiance = albedo / PI * spotIrradiance(p, n) * texelFetch(shadowImage, pixel, 0).r;
    imageStore(directRadiance, pixel, vec4(radiance, 1.0));
}
