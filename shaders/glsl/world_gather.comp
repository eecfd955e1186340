#version 460
#extension GL_GOOGLE_include_directive : require
// world.gather (indirect_method 3): one invocation per cell that world.schedule listed
// (world_schedule.comp), dispatched indirectly for the list's length. A cell gathers work.x VPLs
// for each frame's worth it was given, half from the flux's pool (indirect_vpls.comp: drawn in
// proportion to their flux, a new draw each frame when cached), a run from a place of its own
// for each cell and frame (from its key's hash), half from the VPL map next to it, each weighted
// by its probability; it tests each one's visibility through the voxel grid (world_voxels.glsl),
// and blends the estimate into the cell's mean by the frames' worth on each side.
// lavapipe stops every loop of an invocation once all of them together have run 65,535
// iterations (llvmpipe's loop limiter), which a cell walking hundreds of segments reaches: the
// samples alternate between the two sets, each set's samples are spread over all of it in any
// prefix, and each set's sum is divided by the samples it took, not those it was given, so that
// a gather stopped early is a gather of fewer samples, not a darker one.
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
layout(set = 0, binding = 6, r32ui) uniform coherent uimage2D worldStats;
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

// One VPL of a cell's gather: where it is, its flux, and its weight (the texels of the VPL map
// the sample stands for; 0: no sample).
struct Vpl {
    vec3 position;
    vec3 normal;
    vec3 flux;
    float weight;
};

// What a cell's gather needs of its two sets of VPLs (gatherSetup): both sets take `count`
// samples, the flux pool's from entry `start` on, the disk's of `radius` texels around `center`
// (p's projection into the VPL map) shifted by `shift`.
struct Gather {
    vec3 p, n;
    int count;
    uint start;
    vec2 shift;
    float total;      // the VPL map's luminance
    vec2 center;      // p in the VPL map, in texels
    float radius;     // the disk's, in texels
    float pNear;      // a texel's probability inside the disk
    float texelScale; // the frames the gather stands for, over a full cell's (world_frames)
    float near2;      // the squared distance below which a VPL is taken as at it
};

Gather gatherSetup(vec3 p, vec3 n, int count, uint start, vec2 shift, float frames, float near2) {
    Gather g;
    g.p = p;
    g.n = n;
    g.count = count;
    g.start = start;
    g.shift = shift;
    g.total = texelFetch(vplList, ivec2(POOL, 0), 0).r;
    float side = constants.change.w; // the VPL map's side
    g.radius = max(4.0, side / 16.0);
    g.pNear = 1.0 / (PI * g.radius * g.radius);
    vec4 clip = frame.lightViewProjection * vec4(p, 1.0);
    g.center = (clip.w > 0.0 ? clip.xy / clip.w * 0.5 + 0.5 : vec2(0.5)) * side;
    g.texelScale = frames / constants.cells.z;
    g.near2 = near2;
    return g;
}

// Sample j of `set`, weighted for g.count samples of the set by the balance heuristic of
// multiple importance sampling (Veach 1997) over the two sets, as indirect_importance.comp
// weighs its own two:
// - set 0, the flux's pool from entry g.start on: where the light is;
// - set 1, a texel of the disk around p's projection, placed by the R2 sequence (Roberts 2018)
//   and shifted by g.shift: the VPLs next to p, whose 1/d^2 dominates at creases and contacts and
//   which the flux draws too seldom.
// Any prefix of either set's samples is spread over all of it (the pool is drawn by a
// low-discrepancy sequence too).
Vpl sampleVpl(Gather g, int set, int j) {
    Vpl v;
    v.weight = 0.0;
    if (set == 0) {
        int k = int((g.start + uint(j)) % uint(POOL));
        vec4 fluxProbability = texelFetch(vplList, ivec2(k, 2), 0);
        vec4 position = texelFetch(vplList, ivec2(k, 0), 0);
        vec4 normal = texelFetch(vplList, ivec2(k, 1), 0);
        vec2 texel = vec2(position.w, normal.w) + 0.5;
        float inDisk = distance(texel, g.center) <= g.radius ? g.pNear : 0.0;
        if (fluxProbability.w > 0.0)
            v.weight = 1.0 / (float(g.count) * (fluxProbability.w + inDisk));
        v.position = position.xyz;
        v.normal = normal.xyz;
        v.flux = fluxProbability.rgb;
    } else {
        vec2 u = fract(0.5 + float(j) * vec2(0.7548776662, 0.5698402910) + g.shift);
        float angle = 6.2831853 * u.y;
        ivec2 texel = ivec2(floor(g.center + g.radius * sqrt(u.x) * vec2(cos(angle), sin(angle))));
        int side = int(constants.change.w);
        bool inside = all(greaterThanEqual(texel, ivec2(0))) && all(lessThan(texel, ivec2(side)));
        texel = clamp(texel, ivec2(0), ivec2(side - 1));
        vec4 position = texelFetch(vplPosition, texel, 0);
        v.flux = texelFetch(vplFlux, texel, 0).rgb;
        if (inside && position.w != 0.0)
            v.weight = 1.0 / (float(g.count) * (luminance(v.flux) / g.total + g.pNear));
        v.position = position.xyz;
        v.normal = texelFetch(vplNormal, texel, 0).xyz;
    }
    return v;
}

// The light VPL v sends towards p before p's cosine (`cosP`) and its visibility, times its
// weight, as irradiance / pi; `D` the unit direction to it. 0 where it faces away.
float towardP(Gather g, Vpl v, out vec3 D, out float cosP) {
    vec3 toVpl = v.position - g.p;
    float distance2 = dot(toVpl, toVpl);
    D = toVpl * inversesqrt(max(distance2, 1e-30));
    cosP = dot(g.n, D);
    float cosQ = -dot(v.normal, D);
    if (cosP <= 0.0 || cosQ <= 0.0 || v.weight <= 0.0) return 0.0;
    // The distance clamped to the VPL's footprint, as indirect_gather.glsl clamps it: the clamp
    // is the radius of a disk of a quarter of the area the sample stands for, at least a texel;
    // a VPL that lands next to p then cannot light it more than that area could. A texel of the
    // VPL map is 2 tan(half fov) / side wide per distance from the light.
    vec3 fromLight = v.position - frame.lightPosition.xyz;
    float texel2 = 4.0 * frame.lightFrustum.z * frame.lightFrustum.z / (constants.change.w *
                                                                         constants.change.w);
    float texels2 = max(v.weight * g.texelScale / (4.0 * PI), 1.0);
    float d2 = max(max(distance2, dot(fromLight, fromLight) * texel2 * texels2), g.near2);
    return cosQ * v.weight / (PI * PI * d2);
}

// The cell's gather: sample i of the 2 count is sample i / 2 of set i % 2.
struct Share {
    vec3 sum[2];         // each set's light, each sample weighted for g.count of its set
    vec4 directional[2]; // the same as an L1 spherical harmonic of its luminance
    float taken[2];      // each set's samples that counted (a walk a loop limit stopped does not)
};

// The samples with their visibility through the voxel grid. Russian roulette on the visibility
// test (its walk is most of the gather's cost): a VPL whose light at p, unoccluded, is below
// ROULETTE times the mean of the cell's VPLs before it is tested with that fraction for its
// probability, and counts 1 / probability times where open; a stronger one is always tested.
// The estimate stays unbiased. The segment starts and ends OFFSET voxels off the surfaces, on
// their open sides: a curved surface's voxels stand a voxel or two proud of it, and a segment
// that grazes it from nearer is blocked by its own surface (one uncached frame at 128x128, 0.5 /
// 1.5 / 2.5 voxels: the bunny 0.00256 / 0.00175 / 0.00149, Sponza 0.0110 / 0.0082 / 0.0080).
// The directional sums are the light before p's cosine as an L1 spherical harmonic of its
// luminance (x the sum of c, yzw the sum of c D): f(m) = x / 4 + dot(yzw, m) / 2 approximates
// the irradiance / pi a normal m would receive, which lets a pixel whose normal differs from its
// cell's carry the cell's value over to its own (world_lookup.glsl).
Share gatherCell(Gather g) {
    Share share;
    share.sum[0] = share.sum[1] = vec3(0.0);
    share.directional[0] = share.directional[1] = vec4(0.0);
    share.taken[0] = share.taken[1] = 0.0;
    vec2 seen = vec2(0.0); // the unoccluded light of the VPLs so far that face p, and how many
    float offset = OFFSET * frame.worldGridOrigin.w;
    for (int i = 0; i < 2 * g.count; ++i) {
        int set = i & 1, j = i >> 1;
        Vpl v = sampleVpl(g, set, j);
        vec3 D;
        float cosP;
        float toP = towardP(g, v, D, cosP);
        if (toP > 0.0) {
            float light = luminance(v.flux) * cosP * toP;
            float probability =
                seen.y > 0.0 ? min(1.0, light * seen.y / max(ROULETTE * seen.x, 1e-30)) : 1.0;
            seen += vec2(light, 1.0);
            uint random = worldHash(g.start + uint(i));
            if (float(random >> 8) * (1.0 / 16777216.0) < probability) {
                int segment = voxelSegment(g.p + g.n * offset, v.position + v.normal * offset);
                if (segment == SEGMENT_UNKNOWN) break; // a loop limit: the gather stops here
                if (segment == SEGMENT_OPEN) {
                    toP /= probability;
                    share.sum[set] += v.flux * (cosP * toP);
                    share.directional[set] += luminance(v.flux) * toP * vec4(1.0, D);
                }
            }
        }
        share.taken[set] += 1.0;
    }
    return share;
}

void main() {
    uint slot = gl_GlobalInvocationID.x + gl_GlobalInvocationID.y * 64u * WORLD_GATHER_GROUPS_X;
    uint now = uint(frame.patternFrame);
    int row = int(now) & 1;
    if (slot >= imageLoad(worldStats, ivec2(WORLD_STAT_LISTED, row)).r) return;
    uint listed = texelFetch(gatherList, worldTexel(slot), 0).r;
    uint index = listed & 0x3fffffu;
    float gathered = float(listed >> 22u);
    ivec2 entry = worldTexel(index);
    vec4 point = texelFetch(worldPoints, entry, 0);
    // Where its run of VPLs starts: from its key rather than its entry, so that a cell gathers the
    // same wherever a collision put it.
    uint start = worldHash(texelFetch(worldKeys, entry, 0).r + now * 6271u);
    // The cell stands for the surface across its side: a VPL nearer than NEAR sides lights it
    // as if it stood that far (the cell cannot resolve a contact; one sample that lands there
    // would light the whole cell many times too brightly).
    float side = worldCellSide(worldLevel(distance(point.xyz, frame.cameraPosition.xyz)));
    float near = NEAR * side;
    // The disk's sequence shifted by a random offset in both its coordinates (Cranley and
    // Patterson 1976): a refresh of one frame's worth takes the sequence's first points again,
    // and unshifted in the radius they would stand at the same radii every frame, a bias that
    // no number of refreshes averages away.
    vec2 shift = vec2(worldHash(start) >> 8, worldHash(start ^ 0x9e3779b9u) >> 8) / 16777216.0;
    int count = int(gathered) * constants.work.x / 2;
    Gather g = gatherSetup(point.xyz, unpackCellNormal(point.w), count, start, shift, gathered,
                           near * near);
    if (g.total <= 0.0) g.count = 0; // no light in the map: every sample is 0
    Share share = gatherCell(g);
    // Each set's samples were weighted for `count` of them: its sum over the ones it took,
    // scaled to `count`. (No loops from here on: after a stopped gather they would stop too.)
    float poolScale = share.taken[0] > 0.0 ? float(count) / share.taken[0] : 0.0;
    float diskScale = share.taken[1] > 0.0 ? float(count) / share.taken[1] : 0.0;
    vec3 value = share.sum[0] * poolScale + share.sum[1] * diskScale;
    vec4 directional = share.directional[0] * poolScale + share.directional[1] * diskScale;
    uint cut = uint(2 * g.count) - uint(share.taken[0] + share.taken[1]);
    if (cut > 0u) imageAtomicAdd(worldStats, ivec2(WORLD_STAT_CUT, row), cut);
    vec4 cell = imageLoad(worldIrradiance, entry);
    float before = cell.a;
    vec3 mean = (cell.rgb * before + value * gathered) / (before + gathered);
    imageStore(worldIrradiance, entry, vec4(mean, min(before + gathered, constants.cells.z)));
    vec4 held = imageLoad(worldDirections, entry);
    imageStore(worldDirections, entry,
               (held * before + directional * gathered) / (before + gathered));
}
