#version 460
#extension GL_GOOGLE_include_directive : require
// Reflective shadow map (Dachsbacher & Stamminger 2005): each texel a virtual point light, one
// RGBA32UI texel holding its albedo, the share of the light it reflects, its normal (facing the
// light) and its distance along the light's axis (rsm_vpl.glsl).
#include "shared.h"
#include "common.glsl"

layout(set = 0, binding = 0, std140) uniform FrameBlock { FrameUniforms frame; };
layout(set = 0, binding = 1) uniform sampler2D baseColorTexture;
layout(push_constant) uniform DrawBlock { DrawConstants draw; };
#include "base_color.glsl"

layout(location = 0) in vec3 worldPosition;
layout(location = 1) in vec3 worldNormal;
layout(location = 2) in vec2 uv;
layout(location = 3) in vec4 color;

layout(location = 0) out uvec4 outVpl;

#include "rsm_vpl.glsl"

void main() {
    vec4 albedo = baseColor(uv, color);
    if (albedo.a < draw.material.y) discard;
    vec3 toLight = frame.lightPosition.xyz - worldPosition;
    vec3 n = normalize(worldNormal);
    if (dot(n, toLight) < 0.0) n = -n;
    // Flux through this texel: radiant intensity times the texel's solid angle, which for a
    // texel of a perspective map at angle theta off the axis is (texel area on the unit plane)
    // * cos^3(theta). The surface reflects the fraction `albedo` of it.
    vec3 fromLight = -normalize(toLight);
    float cosAxis = dot(fromLight, frame.lightDirection.xyz);
    float texelSize = 2.0 * frame.lightFrustum.z / frame.lightFrustum.w;
    float solidAngle = texelSize * texelSize * cosAxis * cosAxis * cosAxis;
    float spot = spotAttenuation(fromLight, frame.lightDirection.xyz, frame.lightDirection.w,
                                 frame.lightColor.w);
    // The distance along the axis is never 0: the light's near plane lies in front.
    float axisDepth = dot(worldPosition - frame.lightPosition.xyz, frame.lightDirection.xyz);
    outVpl = packRsmTexel(albedo.rgb, spot * solidAngle, n, axisDepth);
}
