#version 460
#extension GL_GOOGLE_include_directive : require
// Sky visibility beyond the screen: how much of the sky's light reaches each pixel past the
// occluders screen-space AO cannot see (roofs, arcades, anything off screen), from the sky
// visibility maps (sky_maps.glsl) and the scene's floors and walls, which are tested exactly
// (SkyTriangles, shared.h). Per map direction w_k, the pixel's point is looked up in that map
// and its ray toward w_k tested against those triangles; an occluder counts only beyond
// `aoReach` (the AO radius: nearer ones are the AO's, so none is counted twice). The result is a ratio per colour channel,
//   sum_k L(w_k) V_k max(n.w_k, 0) / sum_k L(w_k) max(n.w_k, 0),
// the fraction of the unoccluded sky's irradiance that arrives, which the composite multiplies
// into the closed-form sky term (common.glsl): 1 where nothing far blocks the sky. A property
// of the surface point computed without noise, it is cached as an exact effect: a pixel whose
// history reprojects (and has not blurred past its budget) is skipped (temporal.glsl).
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

// Whether the ray from p toward w meets one of the exact triangles farther than `reach`
// (Moller and Trumbore 1997).
bool blockedExactly(vec3 p, vec3 w, float reach) {
    for (int i = 0; i < exact.count.x; ++i) {
        vec3 a = exact.corners[3 * i].xyz;
        vec3 e1 = exact.corners[3 * i + 1].xyz - a, e2 = exact.corners[3 * i + 2].xyz - a;
        vec3 side = cross(w, e2);
        float det = dot(e1, side);
        if (abs(det) < 1e-20) continue; // the ray runs along the triangle's plane
        vec3 fromA = p - a;
        float u = dot(fromA, side) / det;
        if (u < 0.0 || u > 1.0) continue;
        vec3 up = cross(fromA, e1);
        float v = dot(w, up) / det;
        if (v < 0.0 || u + v > 1.0) continue;
        if (dot(e2, up) / det > reach) return true;
    }
    return false;
}

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
    SkyMapView maps = constants.maps;
    float diameter = 2.0 * maps.sphere.w;
    // Off the surface along its normal, so that it does not shadow itself within a texel.
    vec3 p = position.xyz + n * constants.normalOffset;
    vec3 open = vec3(0.0), arriving = vec3(0.0);
    for (int k = 0; k < maps.tile.y; ++k) {
        vec3 w = skyMapDirection(k, maps.tile.y);
        float cosine = dot(n, w);
        if (cosine <= 0.0) continue;
        vec3 weight = skyRadiance(w, frame.skyZenith.rgb, frame.skyHorizon.rgb,
                                  frame.skyGround.rgb) * cosine;
        vec3 q = skyMapProject(p, w, maps.sphere);
        // Outside the map's square the ray toward w passes beside everything the map holds.
        bool blocked = false;
        if (all(lessThanEqual(abs(q.xy), vec2(1.0)))) {
            float occluder =
                texelFetch(skyMaps, skyMapTexel(q.xy, k, maps.tile.z, maps.tile.w), 0).r;
            // How far toward the sky the nearest surface in this direction lies.
            blocked = (q.z - occluder) * diameter > constants.aoReach;
        }
        blocked = blocked || blockedExactly(p, w, constants.aoReach);
        open += weight;
        arriving += blocked ? vec3(0.0) : weight;
    }
    vec3 visibility = mix(vec3(1.0), arriving / max(open, vec3(1e-20)), greaterThan(open, vec3(0.0)));
    imageStore(sky_visibilityImage, pixel, vec4(visibility, 1.0));
}
