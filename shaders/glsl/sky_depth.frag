#version 460
#extension GL_GOOGLE_include_directive : require
// Sky visibility maps, their alpha-masked draws (the opaque ones have no fragment shader:
// sky_visibility_pass.cpp): depth only; the surfaces (leaves, needles) let the sky through where
// their mask does.
#include "shared.h"

layout(set = 0, binding = 1) uniform sampler2D baseColorTexture;
layout(push_constant) uniform DrawBlock { DrawConstants draw; };
#include "base_color.glsl"

layout(location = 0) in vec2 uv;
layout(location = 1) in vec4 color;

void main() {
    float alpha = baseColor(uv, color).a;
    if (alpha < draw.material.y) discard;
}
