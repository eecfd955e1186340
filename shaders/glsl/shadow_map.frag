#version 460
#extension GL_GOOGLE_include_directive : require
// The shadow map: depth only; alpha-masked surfaces (leaves) let the light through where their
// mask does, as in the RSM (rsm.frag).
#include "shared.h"

layout(set = 0, binding = 1) uniform sampler2D baseColorTexture;
layout(push_constant) uniform DrawBlock { DrawConstants draw; };
#include "base_color.glsl"

layout(location = 0) in vec2 uv;
layout(location = 1) in vec4 color;

void main() {
    // An opaque draw (cutoff 0) reads no texture: most of the map's texels.
    if (draw.material.y > 0.0 && baseColor(uv, color).a < draw.material.y) discard;
}
