#version 460
#extension GL_GOOGLE_include_directive : require
// world.lookup (indirect_method 3): the bounce at every pixel, looked up in the world cache
// (world_cache.glsl) rather than gathered. The value is interpolated between the eight cells
// around the pixel at the level world.insert took (its own, or one coarser or finer where its
// own cell is absent) and with its normal's direction, trilinearly by the pixel's place between
// their centres, so that no cell's edge shows; a cell absent or still empty drops out of the
// weights. Each cell's value is carried over from its own normal to the pixel's by its light's
// directional estimate (toNormal). The debug views (WORLD_VIEW_*) show each pixel's own cell
// instead.
#include "shared.h"
#include "common.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

layout(set = 0, binding = 0, std140) uniform FrameBlock { FrameUniforms frame; };
layout(set = 0, binding = 1) uniform sampler2D gbufferViewDepth;
layout(set = 0, binding = 2) uniform sampler2D gbufferNormal;
layout(set = 0, binding = 3) uniform usampler2D worldKeys;
layout(set = 0, binding = 4) uniform sampler2D worldIrradiance;
layout(set = 0, binding = 5) uniform usampler2D worldUsed;
layout(set = 0, binding = 6, rgba16f) uniform writeonly image2D indirectImage;
layout(set = 0, binding = 7) uniform sampler2D worldPoints;
layout(set = 0, binding = 8) uniform sampler2D worldDirections;
layout(push_constant) uniform WorldBlock { WorldConstants constants; };

#include "gbuffer_position.glsl"
#include "world_cache.glsl"

uint worldKeyAt(ivec2 e) {
    return texelFetch(worldKeys, e, 0).r;
}
float worldSamplesAt(ivec2 e) {
    return texelFetch(worldIrradiance, e, 0).a;
}

// What carries a cell's value over to normal n: the ratio of its light's directional estimate
// for n to that for the cell's own normal (world_gather.comp), at most 4.
float toNormal(ivec2 entry, vec3 n) {
    vec4 d = texelFetch(worldDirections, entry, 0);
    vec3 own = unpackCellNormal(texelFetch(worldPoints, entry, 0).w);
    float there = d.x * 0.25 + 0.5 * dot(d.yzw, own);
    float here = d.x * 0.25 + 0.5 * dot(d.yzw, n);
    return there > 0.0 ? clamp(here / there, 0.0, 4.0) : 1.0;
}

void main() {
    loadPixelToWorld(); // pixel_to_world.glsl
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(pixel, ivec2(frame.viewport.xy)))) return;
    vec4 position = gbufferPosition(pixel);
    if (position.w == 0.0) {
        imageStore(indirectImage, pixel, vec4(0.0));
        return;
    }
    vec3 p = position.xyz;
    vec3 n = texelFetch(gbufferNormal, pixel, 0).xyz;
    int level = worldLevel(distance(p, frame.cameraPosition.xyz));
    int direction = worldDirection(n);
    // The cell and level world.insert took (world_cache.glsl).
    ivec2 own = findPixelCell(p, level, direction);
    int view = constants.work.w;
    if (view != WORLD_VIEW_LIGHT) {
        ivec2 entry = own;
        vec4 shown = vec4(1.0, 0.0, 0.0, 1.0); // no cell: red
        if (entry.x >= 0) {
            vec4 cell = texelFetch(worldIrradiance, entry, 0);
            float unused = float(uint(frame.patternFrame) - texelFetch(worldUsed, entry, 0).r);
            shown = view == WORLD_VIEW_CELLS
                        ? vec4(cell.rgb, 1.0)
                        : vec4(cell.a == 0.0 ? 1.0 : 0.0, cell.a / constants.cells.z,
                               min(unused / float(constants.table.z), 1.0), 1.0);
        }
        imageStore(indirectImage, pixel, shown);
        return;
    }
    // The pixel's place among the centres of the cells around it.
    vec3 u = p / worldCellSide(level) - 0.5;
    ivec3 base = ivec3(floor(u));
    vec3 f = u - vec3(base);
    vec3 sum = vec3(0.0);
    float weights = 0.0;
    // The layer of cells along the normal's axis that holds the pixel first, then the other,
    // each from the corner nearest the pixel. A surface across that axis (a floor, a wall) has
    // cells in one layer only: where the other's nearest corner is absent, so are its others
    // (but where the surface ends at a layer's edge), and its lookups are left out.
    int axis = direction / 2;
    ivec3 nearest = ivec3(greaterThanEqual(f, vec3(0.5)));
    for (int corner = 0; corner < 8; ++corner) {
        ivec3 offset;
        offset[axis] = corner >> 2;
        offset[(axis + 1) % 3] = corner & 1;
        offset[(axis + 2) % 3] = (corner >> 1) & 1;
        offset ^= nearest;
        ivec2 entry = corner == 0 ? own : findCell(worldKey(base + offset, level, direction));
        if (entry.x < 0) {
            if (corner == 4) break;
            continue;
        }
        vec4 cell = texelFetch(worldIrradiance, entry, 0);
        if (cell.a == 0.0) continue;
        vec3 w3 = mix(1.0 - f, f, vec3(offset));
        float w = w3.x * w3.y * w3.z;
        sum += cell.rgb * w * toNormal(entry, n);
        weights += w;
    }
    imageStore(indirectImage, pixel, vec4(weights > 0.0 ? sum / weights : vec3(0.0), 1.0));
}
