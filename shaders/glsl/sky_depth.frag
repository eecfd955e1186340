#version 460
#extension GL_GOOGLE_include_directive : require
// Sky visibility maps: depth only; alpha-masked surfaces (leaves, needles) let the sky through
// where their mask does.
#include "shared.h"

layout(set = 0, binding = 1) uniform sampler2D baseColorTexture;
layout(push_constant) uniform DrawBlock { DrawConstants draw; };

layout(location = 0) in vec2 uv;

void main() {
    float alpha = draw.baseColorFactor.a;
    if (draw.material.x > 0.5) alpha *= texture(baseColorTexture, uv).a;
    if (alpha < draw.material.y) discard;
}
