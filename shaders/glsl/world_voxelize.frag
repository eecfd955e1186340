#version 460
#extension GL_GOOGLE_include_directive : require
// world.voxelize: marks the voxels a fragment covers in the occupancy grid (world_voxels.glsl).
// The viewport has SUPERSAMPLE pixels per voxel along each of its axes, so that a triangle
// smaller than a voxel still covers a pixel centre; along depth, every voxel the fragment's
// depth spans within its pixel is marked, so that a triangle steep to the view leaves no gaps.
#include "shared.h"

layout(constant_id = 0) const int AXIS = 0;
layout(constant_id = 1) const int SUPERSAMPLE = 2;

layout(set = 0, binding = 0, std140) uniform FrameBlock { FrameUniforms frame; };
layout(set = 0, binding = 1) uniform sampler2D baseColorTexture;
layout(set = 0, binding = 2, r32ui) uniform coherent uimage2D voxels;
layout(push_constant) uniform DrawBlock { DrawConstants draw; };
#include "base_color.glsl"
#define WORLD_VOXELS_LAYOUT_ONLY
#include "world_voxels.glsl"

layout(location = 0) in vec2 uv;
layout(location = 1) in vec4 color;

void main() {
    if (baseColor(uv, color).a < draw.material.y) return; // the alpha mask's holes stay open
    ivec3 order = AXIS == 0 ? ivec3(1, 2, 0) : AXIS == 1 ? ivec3(2, 0, 1) : ivec3(0, 1, 2);
    int depthVoxels = frame.worldGridSize[order.z];
    float depth = gl_FragCoord.z * float(depthVoxels);
    // Half the depth's change across the pixel, each way.
    float reach = 0.5 * (abs(dFdx(depth)) + abs(dFdy(depth)));
    int first = clamp(int(floor(depth - reach)), 0, depthVoxels - 1);
    int last = clamp(int(floor(depth + reach)), 0, depthVoxels - 1);
    ivec2 face = ivec2(gl_FragCoord.xy) / SUPERSAMPLE;
    for (int k = first; k <= last; ++k) {
        ivec3 v;
        v[order.x] = face.x;
        v[order.y] = face.y;
        v[order.z] = k;
        if (any(greaterThanEqual(v, frame.worldGridSize.xyz))) continue;
        imageAtomicOr(voxels, blockTexel(v / WORLD_BLOCK) + ivec2(voxelWord(v), 0), voxelBit(v));
    }
}
