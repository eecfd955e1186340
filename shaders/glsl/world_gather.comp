#version 460
#extension GL_GOOGLE_include_directive : require
// world.gather (indirect_method 3): one invocation per cell that world.schedule listed
// (world_schedule.comp), dispatched indirectly for the list's length. A cell gathers work.x VPLs for each frame's worth it was given from the flux's pool
// (indirect_vpls.comp: drawn in proportion to their flux, a new draw each frame when cached), a
// run from a place of its own for each cell and frame (from its key's hash), each weighted by
// its probability, tests each one's visibility through the voxel grid (world_voxels.glsl), and
// blends the estimate into the cell's mean by the frames' worth on each side.
#include "shared.h"
#include "common.glsl"

layout(local_size_x = 64) in;
layout(constant_id = 0) const int POOL = 2048; // the flux's VPLs drawn this frame
const float NEAR = 0.5;   // contacts nearer than this many cell sides are not resolved
const float OFFSET = 2.5; // voxels
const float ROULETTE = 1.0; // below this times the mean light, a VPL's visibility is a gamble

layout(set = 0, binding = 0, std140) uniform FrameBlock { FrameUniforms frame; };
layout(set = 0, binding = 1) uniform usampler2D voxels;
layout(set = 0, binding = 2) uniform usampler2D voxelDistance;
layout(set = 0, binding = 3) uniform sampler2D vplList;
layout(set = 0, binding = 4, rgba32f) uniform image2D worldIrradiance;
layout(set = 0, binding = 5) uniform sampler2D worldPoints;
layout(set = 0, binding = 6) uniform usampler2D worldStats;
layout(set = 0, binding = 7) uniform usampler2D gatherList;
layout(set = 0, binding = 8) uniform usampler2D worldKeys;
// The VPL map (indirect_vpls.comp: the RSM clustered): position (w 1 where it holds light),
// normal, flux.
layout(set = 0, binding = 9) uniform sampler2D vplPosition;
layout(set = 0, binding = 10) uniform sampler2D vplNormal;
layout(set = 0, binding = 11) uniform sampler2D vplFlux;
layout(set = 0, binding = 12, rgba32f) uniform image2D worldDirections;
layout(push_constant) uniform WorldBlock { WorldConstants constants; };

#include "world_cache.glsl"
#include "world_voxels.glsl"

float luminance(vec3 c) {
    return dot(c, vec3(0.2126, 0.7152, 0.0722));
}

// The light one VPL (at q, normal nq, flux `flux`) brings to p (normal n) as irradiance / pi,
// times `weight` (the texels of the VPL map it stands for); 0 where it is hidden in the voxel
// grid. `texelScale` turns the weight into the texels a full cell's sample stands for.
vec3 vplLight(vec3 p, vec3 n, vec3 q, vec3 nq, vec3 flux, float weight, float texelScale,
              float near2, inout vec4 directional, inout vec2 seen, uint random) {
    vec3 toVpl = q - p;
    float distance2 = dot(toVpl, toVpl);
    vec3 D = toVpl * inversesqrt(max(distance2, 1e-30));
    float cosP = dot(n, D), cosQ = -dot(nq, D);
    if (cosP <= 0.0 || cosQ <= 0.0 || weight <= 0.0) return vec3(0.0);
    // The distance clamped to the VPL's footprint, as indirect_gather.glsl clamps it: the clamp
    // is the radius of a disk of a quarter of the area the sample stands for, at least a texel;
    // a VPL that lands next to p then cannot light it more than that area could. A texel of the
    // VPL map is 2 tan(half fov) / side wide per distance from the light.
    vec3 fromLight = q - frame.lightPosition.xyz;
    float texel2 = 4.0 * frame.lightFrustum.z * frame.lightFrustum.z / (constants.change.w *
                                                                         constants.change.w);
    float texels2 = max(weight * texelScale / (4.0 * PI), 1.0);
    float d2 = max(max(distance2, dot(fromLight, fromLight) * texel2 * texels2), near2);
    // The segment starts and ends OFFSET voxels off the surfaces, on their open sides: a curved
    // surface's voxels stand a voxel or two proud of it, and a segment that grazes it from
    // nearer is blocked by its own surface (one uncached frame at 128x128, 0.5 / 1.5 / 2.5
    // voxels: the bunny 0.00256 / 0.00175 / 0.00149, Sponza 0.0110 / 0.0082 / 0.0080).
    float toP = cosQ * weight / (PI * PI * d2); // the light towards p, before p's cosine
    // Russian roulette on the visibility test (its walk is most of the gather's cost): a VPL
    // whose light at p, unoccluded, is below ROULETTE times the mean of the gather's VPLs before
    // it is tested with that fraction for its probability, and counts 1 / probability times where
    // open; a stronger one is always tested. The estimate stays unbiased.
    float light = luminance(flux) * cosP * toP;
    float probability = seen.y > 0.0 ? min(1.0, light * seen.y / (ROULETTE * seen.x)) : 1.0;
    seen += vec2(light, 1.0);
    if (float(random >> 8) * (1.0 / 16777216.0) >= probability) return vec3(0.0);
    float offset = OFFSET * frame.worldGridOrigin.w;
    if (!voxelSegmentOpen(p + n * offset, q + nq * offset)) return vec3(0.0);
    toP /= probability;
    directional += luminance(flux) * toP * vec4(1.0, D);
    return flux * (cosP * toP);
}

// Irradiance / pi at p (normal n) from two sets of VPLs of the VPL map, weighted together by the
// balance heuristic of multiple importance sampling (Veach 1997), as indirect_importance.comp
// weighs its own two:
// - `count` of the flux's pool, from entry `start` on: where the light is;
// - `count` texels of a disk of NEAR_RADIUS texels around p's projection into the map, a
//   spiral turned by `turn`: the VPLs next to p, whose 1/d^2 dominates at creases and contacts
//   and which the flux draws too seldom.
// `frames` is the frames' worth the gather stands for (of constants.cells.z in a full cell).
// `directional` receives the same VPLs' light before p's cosine as an L1 spherical harmonic of
// its luminance (x the sum of c, yzw the sum of c D): f(m) = x / 4 + dot(yzw, m) / 2
// approximates the irradiance / pi a normal m would receive, which lets a pixel whose normal
// differs from its cell's carry the cell's value over to its own (world_lookup.comp).
vec3 gather(vec3 p, vec3 n, int count, uint start, float turn, float frames, float near2,
            out vec4 directional) {
    directional = vec4(0.0);
    vec2 seen = vec2(0.0); // the unoccluded light of the VPLs so far, and how many
    float total = texelFetch(vplList, ivec2(POOL, 0), 0).r;
    if (total <= 0.0) return vec3(0.0);
    float side = constants.change.w; // the VPL map's side
    float radius = max(4.0, side / 16.0);
    float pNear = 1.0 / (PI * radius * radius); // a texel's, inside the disk
    vec4 clip = frame.lightViewProjection * vec4(p, 1.0);
    vec2 center = (clip.w > 0.0 ? clip.xy / clip.w * 0.5 + 0.5 : vec2(0.5)) * side;
    float texelScale = frames / constants.cells.z;
    vec3 sum = vec3(0.0);
    for (int j = 0; j < count; ++j) {
        int k = int((start + uint(j)) % uint(POOL));
        vec4 fluxProbability = texelFetch(vplList, ivec2(k, 2), 0);
        float pFlux = fluxProbability.w;
        if (pFlux <= 0.0) continue;
        vec4 position = texelFetch(vplList, ivec2(k, 0), 0);
        vec4 normal = texelFetch(vplList, ivec2(k, 1), 0);
        vec2 texel = vec2(position.w, normal.w) + 0.5;
        float inDisk = distance(texel, center) <= radius ? pNear : 0.0;
        float weight = 1.0 / (float(count) * (pFlux + inDisk));
        sum += vplLight(p, n, position.xyz, normal.xyz, fluxProbability.rgb, weight, texelScale,
                        near2, directional, seen, worldHash(start + uint(j) * 2u));
    }
    for (int j = 0; j < count; ++j) {
        float r = radius * sqrt((float(j) + 0.5) / float(count));
        float angle = float(j) * 2.39996323 + turn; // the golden angle
        ivec2 texel = ivec2(floor(center + r * vec2(cos(angle), sin(angle))));
        if (any(lessThan(texel, ivec2(0))) || any(greaterThanEqual(texel, ivec2(side)))) continue;
        vec4 position = texelFetch(vplPosition, texel, 0);
        if (position.w == 0.0) continue;
        vec3 flux = texelFetch(vplFlux, texel, 0).rgb;
        float pFlux = luminance(flux) / total;
        float weight = 1.0 / (float(count) * (pFlux + pNear));
        sum += vplLight(p, n, position.xyz, texelFetch(vplNormal, texel, 0).xyz, flux, weight,
                        texelScale, near2, directional, seen, worldHash(start + uint(j) * 2u + 1u));
    }
    return sum;
}

void main() {
    uint slot = gl_GlobalInvocationID.x;
    uint now = uint(frame.patternFrame);
    if (slot >= texelFetch(worldStats, ivec2(WORLD_STAT_LISTED, int(now) & 1), 0).r) return;
    uint listed = texelFetch(gatherList, worldTexel(slot), 0).r;
    uint index = listed & 0x3fffffu;
    float gathered = float(listed >> 22u);
    ivec2 entry = worldTexel(index);
    vec4 cell = imageLoad(worldIrradiance, entry);
    vec4 point = texelFetch(worldPoints, entry, 0);
    vec3 n = unpackCellNormal(point.w);
    // Where its run of VPLs starts: from its key rather than its entry, so that a cell gathers the
    // same wherever a collision put it.
    uint start = worldHash(texelFetch(worldKeys, entry, 0).r + now * 6271u);
    // The cell stands for the surface across its side: a VPL nearer than NEAR sides lights it
    // as if it stood that far (the cell cannot resolve a contact; one sample that lands there
    // would light the whole cell many times too brightly).
    float side = worldCellSide(worldLevel(distance(point.xyz, frame.cameraPosition.xyz)));
    float near = NEAR * side;
    float turn = 6.2831853 * float(worldHash(start) >> 8) / 16777216.0;
    vec4 directional;
    vec3 value = gather(point.xyz, n, int(gathered) * constants.work.x / 2, start, turn, gathered,
                        near * near, directional);
    float count = cell.a;
    vec3 mean = (cell.rgb * count + value * gathered) / (count + gathered);
    imageStore(worldIrradiance, entry, vec4(mean, min(count + gathered, constants.cells.z)));
    vec4 directions = imageLoad(worldDirections, entry);
    imageStore(worldDirections, entry,
               (directions * count + directional * gathered) / (count + gathered));
}
