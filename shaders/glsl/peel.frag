#version 460
#extension GL_GOOGLE_include_directive : require
// Depth peeling (SSDO paper section 4): the second depth layer, the nearest surface behind the
// one the G-buffer holds at each pixel. Fragments at or in front of the first layer are
// discarded; what remains is depth-tested as usual, so the nearest of them wins.
#include "shared.h"

layout(set = 0, binding = 0, std140) uniform FrameBlock { FrameUniforms frame; };
layout(set = 0, binding = 1) uniform sampler2D baseColorTexture;
layout(set = 0, binding = 2) uniform sampler2D firstLayerViewDepth; // the G-buffer's
layout(push_constant) uniform DrawBlock { DrawConstants draw; };
#include "base_color.glsl"

layout(location = 0) in vec3 worldPosition;
layout(location = 1) in vec3 worldNormal;
layout(location = 2) in vec2 uv;
layout(location = 3) in vec4 color;

layout(location = 0) out vec4 outPosition;

float viewDepth(vec3 world) { return -(frame.view * vec4(world, 1.0)).z; }

void main() {
    vec4 albedo = baseColor(uv, color);
    if (albedo.a < draw.material.y) discard;
    float first = texelFetch(firstLayerViewDepth, ivec2(gl_FragCoord.xy), 0).r;
    // A sliver of relative depth keeps the first layer's own surface from peeling itself.
    if (first != 0.0 && viewDepth(worldPosition) <= first * 1.002) discard;
    outPosition = vec4(worldPosition, 1.0);
}
