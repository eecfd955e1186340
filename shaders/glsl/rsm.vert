#version 460
#extension GL_GOOGLE_include_directive : require
// Reflective shadow map: the scene seen from the spot light.
#include "shared.h"

layout(location = 0) in vec3 inPosition;
layout(location = 1) in vec3 inNormal;
layout(location = 2) in vec2 inUv;
layout(location = 3) in vec4 inColor;

layout(set = 0, binding = 0, std140) uniform FrameBlock { FrameUniforms frame; };
layout(push_constant) uniform DrawBlock { DrawConstants draw; };

layout(location = 0) out vec3 worldPosition;
layout(location = 1) out vec3 worldNormal;
layout(location = 2) out vec2 uv;
layout(location = 3) out vec4 color;

void main() {
    vec4 world = draw.model * vec4(inPosition, 1.0);
    worldPosition = world.xyz;
    worldNormal = mat3(transpose(inverse(draw.model))) * inNormal;
    uv = inUv;
    color = inColor;
    gl_Position = frame.lightViewProjection * world;
}
