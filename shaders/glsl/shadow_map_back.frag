#version 460
#extension GL_GOOGLE_include_directive : require
// The shadow map's back faces: the depth of the nearest surface that faces away from the light,
// where a ray from the light leaves the solid it entered at the shadow map's depth (shadow.comp's
// light-space horizons). Surfaces that face the light are discarded; so are an alpha mask's
// holes, as in shadow_map.frag.
#include "shared.h"

layout(set = 0, binding = 0, std140) uniform FrameBlock { FrameUniforms frame; };
layout(set = 0, binding = 1) uniform sampler2D baseColorTexture;
layout(push_constant) uniform DrawBlock { DrawConstants draw; };
#include "base_color.glsl"

layout(location = 0) in vec2 uv;
layout(location = 1) in vec4 color;
layout(location = 2) in vec3 position;
layout(location = 3) in vec3 normal;

void main() {
    if (dot(normal, frame.lightPosition.xyz - position) > 0.0) discard;
    if (draw.material.y > 0.0 && baseColor(uv, color).a < draw.material.y) discard;
}
