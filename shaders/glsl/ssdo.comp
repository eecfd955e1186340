#version 460
#extension GL_GOOGLE_include_directive : require
// Screen-space directional occlusion (Ritschel, Grosch, Seidel 2009, sections 3-4). SAMPLES
// directions w_i over p's hemisphere, each stepped a length in [0, r_max]; the step's end is an
// occluder when it lies behind the depth stored where it projects.
// Sky: L_dir = sum (rho/pi) L_sky(w_i) V(w_i) cos(theta_i) dw, estimated with cosine-weighted
// directions, for which (cos/pdf) = pi and the sum becomes rho * mean(L_sky V).
// Bounce: each occluding sample is a patch of area A_s = pi r_max^2 / N at the G-buffer point
// it projects to, radiating that pixel's direct radiance L_pixel:
// L_ind = sum (rho/pi) L_pixel (1 - V) A_s cos(theta_s) cos(theta_r) / d^2 (back-facing senders
// skipped; d clamped below at the patch's own radius, sqrt(A_s / pi), in place of the paper's
// clamp to 1 unit, so that one setting serves every scene scale), scaled by a user factor.
#include "shared.h"
#include "common.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(constant_id = 0) const int SAMPLES = 16;
layout(constant_id = 1) const int PEELING = 0;

layout(set = 0, binding = 0, std140) uniform FrameBlock { FrameUniforms frame; };
layout(set = 0, binding = 1) uniform sampler2D gbufferViewDepth;
layout(set = 0, binding = 2) uniform sampler2D gbufferNormal;
layout(set = 0, binding = 3) uniform sampler2D gbufferAlbedo;
layout(set = 0, binding = 4) uniform sampler2D directRadiance;
layout(set = 0, binding = 5) uniform sampler2D secondLayer; // peel.position (PEELING only)
layout(set = 0, binding = 6) uniform sampler2D historyViewDepth;
layout(set = 0, binding = 7) uniform usampler2D reprojection;
layout(set = 0, binding = 8) uniform sampler2D historyCount;
layout(set = 0, binding = 9, rgba16f) uniform writeonly image2D ssdoImage;
layout(push_constant) uniform SsdoBlock { SsdoConstants constants; };

#include "gbuffer_position.glsl"
#include "screen_space.glsl"
#include "temporal.glsl"

void main() {
    loadPixelToWorld(); // pixel_to_world.glsl
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(pixel, ivec2(frame.viewport.xy)))) return;
    vec4 position = gbufferPosition(pixel);
    if (position.w == 0.0) {
        imageStore(ssdoImage, pixel, vec4(0.0, 0.0, 0.0, 1.0));
        return;
    }
    vec3 p = position.xyz;
    if (converged(pixel, p, constants.cache)) {
        imageStore(ssdoImage, pixel, SKIPPED); // converged: the cache holds the value
        return;
    }
    vec3 n = texelFetch(gbufferNormal, pixel, 0).xyz;
    vec3 albedo = texelFetch(gbufferAlbedo, pixel, 0).rgb;
    float rMax = constants.rMax * constants.scale;
    float patchArea = PI * rMax * rMax / float(SAMPLES);
    float minDistance2 = patchArea / PI;
    mat3 frameToWorld = tangentFrame(n);
    float rotation = pixelRotation(pixel) + constants.rotation;
    // Step lengths are stratified too, offset per pixel so neighbours take different ones.
    float stepOffset = fract(rotation * 0.1591549);

    vec3 sky = vec3(0.0), bounce = vec3(0.0);
    for (int i = 0; i < SAMPLES; ++i) {
        vec2 disk = vogelDisk(i, SAMPLES, rotation);
        vec3 local = vec3(disk, sqrt(max(1.0 - dot(disk, disk), 0.0))); // cosine-weighted
        vec3 w = frameToWorld * local;
        float stepLength = rMax * fract((float(i) + 0.5) / float(SAMPLES) + stepOffset);
        vec3 projected = projectToPixel(p + w * stepLength);
        bool occluded = false;
        vec4 sender = vec4(0.0);
        ivec2 senderPixel;
        if (projected.z > 0.0 && insideViewport(projected.xy)) {
            senderPixel = ivec2(projected.xy);
            sender = gbufferPosition(senderPixel);
            occluded = sender.w != 0.0 && projected.z > viewDepth(sender.xyz);
            // With depth peeling (paper section 4), a sample behind the second layer lies in the
            // open space behind a thin object, not inside it.
            if (PEELING != 0 && occluded) {
                vec4 back = texelFetch(secondLayer, senderPixel, 0);
                occluded = back.w == 0.0 || projected.z < viewDepth(back.xyz);
            }
        }
        if (!occluded) {
            sky += skyRadiance(w, frame.skyZenith.rgb, frame.skyHorizon.rgb, frame.skyGround.rgb);
            continue;
        }
        vec3 toReceiver = p - sender.xyz;
        float d2 = dot(toReceiver, toReceiver);
        vec3 dir = toReceiver * inversesqrt(max(d2, tinyLength2()));
        vec3 senderNormal = texelFetch(gbufferNormal, senderPixel, 0).xyz;
        float cosS = dot(senderNormal, dir);
        float cosR = dot(n, -dir);
        if (cosS <= 0.0 || cosR <= 0.0) continue; // back-facing sender, or behind the receiver
        vec3 senderRadiance = texelFetch(directRadiance, senderPixel, 0).rgb;
        bounce += senderRadiance * patchArea * cosS * cosR / max(d2, minDistance2);
    }
    vec3 radiance = albedo * sky / float(SAMPLES) + albedo / PI * bounce * constants.bounceStrength;
    imageStore(ssdoImage, pixel, vec4(radiance, 1.0));
}
