#version 460
#extension GL_GOOGLE_include_directive : require
// Screen-space contact shadows (SSDO paper section 5): the shadow map's bias lifts shadows off
// the surfaces that cast them. For a pixel the shadow map calls (partly) lit, STEPS samples
// along the segment toward the light, as long as that bias is in the world (CONTACT_TEXELS
// shadow-map texels at the pixel), are tested against the G-buffer depth; a sample behind the
// visible surface there (by less than the segment's length, so that far foreground objects do
// not count) is an occluder, and the pixel is put in shadow.
#include "shared.h"
#include "common.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(constant_id = 0) const int STEPS = 8;

layout(set = 0, binding = 0, std140) uniform FrameBlock { FrameUniforms frame; };
layout(set = 0, binding = 1) uniform sampler2D gbufferPosition;
layout(set = 0, binding = 2) uniform sampler2D gbufferNormal;
layout(set = 0, binding = 3) uniform sampler2D shadowImage;
layout(set = 0, binding = 4, rgba16f) uniform writeonly image2D contactShadow;
layout(push_constant) uniform ContactBlock { ContactConstants constants; };

#include "screen_space.glsl"

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(pixel, ivec2(frame.viewport.xy)))) return;
    vec4 position = texelFetch(gbufferPosition, pixel, 0);
    float lit = texelFetch(shadowImage, pixel, 0).r;
    if (position.w == 0.0 || lit == 0.0) {
        imageStore(contactShadow, pixel, vec4(vec3(lit), 1.0));
        return;
    }
    vec3 p = position.xyz;
    vec3 n = texelFetch(gbufferNormal, pixel, 0).xyz;
    vec3 toLight = frame.lightPosition.xyz - p;
    float texelAtP = length(toLight) * 2.0 * frame.lightFrustum.z / frame.lightFrustum.w;
    float segment = constants.params.x * texelAtP;
    vec3 l = normalize(toLight);
    float footprint = 1.0 / pixelsPerUnit(viewDepth(p));
    vec3 start = p + n * footprint; // off the surface, so it does not find itself
    for (int i = 1; i <= STEPS; ++i) {
        vec3 q = start + l * (segment * float(i) / float(STEPS));
        vec3 projected = projectToPixel(q);
        if (projected.z <= 0.0 || !insideViewport(projected.xy)) break;
        vec4 stored = texelFetch(gbufferPosition, ivec2(projected.xy), 0);
        if (stored.w == 0.0) continue;
        float behind = projected.z - viewDepth(stored.xyz);
        if (behind > footprint && behind < segment) {
            lit = 0.0;
            break;
        }
    }
    imageStore(contactShadow, pixel, vec4(vec3(lit), 1.0));
}
