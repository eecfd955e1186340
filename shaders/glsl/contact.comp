#version 460
#extension GL_GOOGLE_include_directive : require
// Screen-space contact shadows (SSDO paper section 5): the shadow map's bias lifts shadows off
// the surfaces that cast them. For a pixel the shadow map calls (partly) lit, STEPS samples
// along the segment toward the light, as long as that bias is in the world (CONTACT_TEXELS
// shadow-map texels at the pixel), are tested against the G-buffer depth. With the second depth
// layer (depth peeling, paper section 4) a sample is an occluder when it lies between the two
// layers, inside the object the camera sees there; with one layer, when it is behind the visible
// surface by less than the segment's length (a thickness guess, so that far foreground objects
// do not count). An occluded sample puts the pixel in shadow.
#include "shared.h"
#include "common.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(constant_id = 0) const int STEPS = 8;
layout(constant_id = 1) const int PEELING = 0;

layout(set = 0, binding = 0, std140) uniform FrameBlock { FrameUniforms frame; };
layout(set = 0, binding = 1) uniform sampler2D gbufferViewDepth;
layout(set = 0, binding = 2) uniform sampler2D gbufferNormal;
layout(set = 0, binding = 3) uniform sampler2D shadowImage;
layout(set = 0, binding = 4) uniform sampler2D secondLayer; // peel.position (PEELING only)
layout(set = 0, binding = 5, rgba16f) uniform writeonly image2D contactShadow;
layout(push_constant) uniform ContactBlock { ContactConstants constants; };

#include "gbuffer_position.glsl"
#include "screen_space.glsl"

void main() {
    loadPixelToWorld(); // pixel_to_world.glsl
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(pixel, ivec2(frame.viewport.xy)))) return;
    vec4 position = gbufferPosition(pixel);
    // r: the shadow term with contact shadows; g: the shadow map's term alone (debug view).
    float mapped = texelFetch(shadowImage, pixel, 0).r, lit = mapped;
    if (position.w == 0.0 || lit == 0.0) {
        imageStore(contactShadow, pixel, vec4(lit, mapped, lit, 1.0));
        return;
    }
    vec3 p = position.xyz;
    vec3 n = texelFetch(gbufferNormal, pixel, 0).xyz;
    vec3 toLight = frame.lightPosition.xyz - p;
    float texelAtP = length(toLight) * 2.0 * frame.lightFrustum.z / frame.lightFrustum.w;
    float segment = constants.segmentTexels * texelAtP;
    vec3 l = normalize(toLight);
    float footprint = 1.0 / pixelsPerUnit(viewDepth(p));
    vec3 start = p + n * footprint; // off the surface, so it does not find itself
    for (int i = 1; i <= STEPS; ++i) {
        vec3 q = start + l * (segment * float(i) / float(STEPS));
        vec3 projected = projectToPixel(q);
        if (projected.z <= 0.0 || !insideViewport(projected.xy)) break;
        vec4 stored = gbufferPosition(ivec2(projected.xy));
        if (stored.w == 0.0) continue;
        // Within one pixel a surface seen at a grazing angle spans a depth of about a footprint
        // over the cosine: a sample nearer behind it than that may be in front of it in truth.
        vec3 storedNormal = texelFetch(gbufferNormal, ivec2(projected.xy), 0).xyz;
        vec3 toCamera = normalize(frame.cameraPosition.xyz - stored.xyz);
        float thickness = 2.0 * footprint / max(abs(dot(storedNormal, toCamera)), 0.1);
        float behind = projected.z - viewDepth(stored.xyz);
        bool inside = behind > thickness && behind < segment;
        if (PEELING != 0 && behind > thickness) {
            vec4 back = texelFetch(secondLayer, ivec2(projected.xy), 0);
            inside = back.w != 0.0 && projected.z < viewDepth(back.xyz);
        }
        if (inside) {
            lit = 0.0;
            break;
        }
    }
    imageStore(contactShadow, pixel, vec4(lit, mapped, lit, 1.0));
}
