#version 460
#extension GL_GOOGLE_include_directive : require
// Sky visibility maps: the scene's depth seen from one direction of the sky (orthographic,
// around its bounding sphere), into that direction's tile of the atlas (the viewport).
#include "shared.h"
#include "sky_maps.glsl"

layout(location = 0) in vec3 inPosition;
layout(location = 1) in vec3 inNormal;
layout(location = 2) in vec2 inUv;
layout(location = 3) in vec4 inColor;

layout(set = 0, binding = 0, std140) uniform MapBlock { SkyMapView map; };
layout(push_constant) uniform DrawBlock { DrawConstants draw; };

layout(location = 0) out vec2 uv;
layout(location = 1) out vec4 color;

void main() {
    vec3 world = (draw.model * vec4(inPosition, 1.0)).xyz;
    vec3 p = skyMapProject(world, skyMapDirection(map.tile.x, map.tile.y), map.sphere);
    uv = inUv;
    color = inColor;
    gl_Position = vec4(p.xy, p.z, 1.0);
}
