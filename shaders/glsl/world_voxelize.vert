#version 460
#extension GL_GOOGLE_include_directive : require
// world.voxelize: the scene seen along one axis of the voxel grid (AXIS 0, 1, 2: x, y, z), in
// an orthographic view that maps the grid's other two axes onto the viewport, a voxel to
// SUPERSAMPLE pixels (the viewport holds the largest grid, worldGridSize.w voxels a side), and
// the grid's extent along AXIS onto depth [0, 1]. Drawn once along each axis, so that every
// triangle is seen along the axis it faces most (world_voxelize.frag).
#include "shared.h"

layout(constant_id = 0) const int AXIS = 0;

layout(location = 0) in vec3 inPosition;
layout(location = 1) in vec3 inNormal;
layout(location = 2) in vec2 inUv;
layout(location = 3) in vec4 inColor;

layout(set = 0, binding = 0, std140) uniform FrameBlock { FrameUniforms frame; };
layout(push_constant) uniform DrawBlock { DrawConstants draw; };

layout(location = 0) out vec2 uv;
layout(location = 1) out vec4 color;

void main() {
    vec3 world = (draw.model * vec4(inPosition, 1.0)).xyz;
    vec3 g = (world - frame.worldGridOrigin.xyz) / frame.worldGridOrigin.w; // in voxels
    float viewport = float(frame.worldGridSize.w);
    // The viewport's axes and depth: the two axes after AXIS, in order, then AXIS.
    ivec3 order = AXIS == 0 ? ivec3(1, 2, 0) : AXIS == 1 ? ivec3(2, 0, 1) : ivec3(0, 1, 2);
    vec3 s = vec3(g[order.x] / viewport, g[order.y] / viewport,
                  g[order.z] / float(frame.worldGridSize[order.z]));
    gl_Position = vec4(s.xy * 2.0 - 1.0, s.z, 1.0);
    uv = inUv;
    color = inColor;
}
