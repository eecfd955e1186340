#version 460
#extension GL_GOOGLE_include_directive : require
// G-buffer: view depth (0 where there is no geometry; the world position follows from it,
// gbuffer_position.glsl), world normal facing the camera (surfaces are two-sided), Lambertian
// albedo.
#include "shared.h"

layout(set = 0, binding = 0, std140) uniform FrameBlock { FrameUniforms frame; };
layout(set = 0, binding = 1) uniform sampler2D baseColorTexture;
layout(push_constant) uniform DrawBlock { DrawConstants draw; };
#include "base_color.glsl"

layout(location = 0) in vec3 worldPosition;
layout(location = 1) in vec3 worldNormal;
layout(location = 2) in vec2 uv;
layout(location = 3) in vec4 color;

layout(location = 0) out float outViewDepth;
layout(location = 1) out vec4 outNormal;
layout(location = 2) out vec4 outAlbedo;

void main() {
    vec4 albedo = baseColor(uv, color);
    if (albedo.a < draw.material.y) discard;
    vec3 n = normalize(worldNormal);
    if (dot(n, frame.cameraPosition.xyz - worldPosition) < 0.0) n = -n;
    outViewDepth = 1.0 / gl_FragCoord.w; // 1 / clip w: the distance along the view axis
    outNormal = vec4(n, 0.0);
    outAlbedo = vec4(albedo.rgb, 1.0);
}
