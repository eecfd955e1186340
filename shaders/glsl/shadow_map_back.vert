#version 460
#extension GL_GOOGLE_include_directive : require
// The shadow map's back faces: the scene seen from the spot light, each surface with the side it
// turns to the light (shadow_map_back_pass.cpp).
#include "shared.h"

layout(location = 0) in vec3 inPosition;
layout(location = 1) in vec3 inNormal;
layout(location = 2) in vec2 inUv;
layout(location = 3) in vec4 inColor;

layout(set = 0, binding = 0, std140) uniform FrameBlock { FrameUniforms frame; };
layout(push_constant) uniform DrawBlock { DrawConstants draw; };

layout(location = 0) out vec2 uv;
layout(location = 1) out vec4 color;
layout(location = 2) out vec3 position;
layout(location = 3) out vec3 normal;

void main() {
    uv = inUv;
    color = inColor;
    vec4 world = draw.model * vec4(inPosition, 1.0);
    position = world.xyz;
    normal = mat3(draw.model) * inNormal;
    gl_Position = frame.lightViewProjection * world;
}
