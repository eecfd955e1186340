#version 460
#extension GL_GOOGLE_include_directive : require
// The shadow map's alpha-masked draws (the opaque ones have no fragment shader:
// shadow_map_pass.cpp): depth only; the surfaces (leaves) let the light through where their mask
// does, as in the RSM (rsm.frag).
#include "shared.h"

layout(set = 0, binding = 1) uniform sampler2D baseColorTexture;
layout(push_constant) uniform DrawBlock { DrawConstants draw; };
#include "base_color.glsl"

layout(location = 0) in vec2 uv;
layout(location = 1) in vec4 color;

void main() {
    if (baseColor(uv, color).a < draw.material.y) discard;
}
