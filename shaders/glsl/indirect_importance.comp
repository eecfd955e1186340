#version 460
#extension GL_GOOGLE_include_directive : require
// One-bounce indirect light with VPLs chosen by importance (indirect_method 2): interleaved as
// in indirect_interleaved.comp (each pixel of a k x k block gathers one of k^2 disjoint
// subsets, and indirect_reconstruct.comp puts them back together), from two sets of VPLs:
// - the pattern's VPLS texels around the pixel's projection into the RSM, dense near it
//   (shared_vpls.h vplPattern: density 1/r), which finds the close VPLs whose 1/d^2 dominates at
//   creases and contacts;
// - FLUX_VPLS texels drawn in proportion to their reflected flux (indirect_vpls.comp), the same
//   list for every pixel, which puts the VPLs where the light is.
// Each VPL is weighted by both densities, 1 / (n_pattern p_pattern + n_flux p_flux) (the
// balance heuristic of multiple importance sampling, Veach 1997), so the sum stays an unbiased
// estimate of the whole map's light whatever the mix. Then the visibility test, the costly part,
// runs on TESTS of the subset's VPLs only, drawn in proportion to the light each brings
// unoccluded (systematic sampling: each is tested n_i times in expectation m L_i / L, with
// L_i its luminance and L their sum, and weighted L / (m L_i)): bright VPLs are tested, dim
// ones rarely, and the estimate is still unbiased. A converged pixel is skipped.
#include "shared.h"
#include "common.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(constant_id = 0) const int VPLS = 512;
layout(constant_id = 1) const int VISIBILITY = 1;
layout(constant_id = 2) const int VISIBILITY_STEPS = 6;
layout(constant_id = 3) const int INTERLEAVE = 4;
layout(constant_id = 4) const int RADIUS = 8; // the filter's, for the refresh tile's margin
layout(constant_id = 5) const int FLUX_VPLS = 256;
layout(constant_id = 6) const int TESTS = 8; // visibility tests a pixel; 0: every VPL
layout(constant_id = 7) const int POOL = 2048; // the flux's VPLs drawn this frame
layout(constant_id = 8) const int MAP_SIZE = 256; // the VPL map's side
layout(constant_id = 9) const int PEELING = 0; // the visibility test between two depth layers
layout(constant_id = 10) const int LIGHT_CHECK = 1; // the visibility test asks the light's map
const int SUBSETS = INTERLEAVE * INTERLEAVE;
const int CANDIDATES = (VPLS + SUBSETS - 1) / SUBSETS + (FLUX_VPLS + SUBSETS - 1) / SUBSETS;
// At most every candidate is tested.
const int MAX_TESTS = TESTS == 0 || TESTS > CANDIDATES ? CANDIDATES : TESTS;

layout(set = 0, binding = 0, std140) uniform FrameBlock { FrameUniforms frame; };
layout(set = 0, binding = 1) uniform sampler2D gbufferViewDepth;
layout(set = 0, binding = 2) uniform sampler2D gbufferNormal;
// The VPL map (indirect_vpls.comp: the RSM clustered), read in place of the RSM.
layout(set = 0, binding = 3) uniform sampler2D vplPosition;
layout(set = 0, binding = 4) uniform sampler2D vplNormal;
layout(set = 0, binding = 5) uniform sampler2D vplFlux;
layout(set = 0, binding = 6) uniform sampler2D vplList;
layout(set = 0, binding = 7) uniform sampler2D historyViewDepth;
layout(set = 0, binding = 8) uniform usampler2D reprojection;
layout(set = 0, binding = 9) uniform sampler2D historyCount;
layout(set = 0, binding = 10, rgba16f) uniform writeonly image2D interleavedIndirect;
layout(set = 0, binding = 11, rgba16f) uniform writeonly image2D interleavedDirectional;
layout(set = 0, binding = 12) uniform sampler2D secondLayer; // peel.position (PEELING only)
layout(set = 0, binding = 13) uniform sampler2D lightDepthMin; // light_depth_min (LIGHT_CHECK only)
layout(push_constant) uniform IndirectBlock { IndirectConstants constants; };

#include "gbuffer_position.glsl"
#include "screen_space.glsl"
#include "temporal.glsl"
#include "indirect_visibility.glsl"

float luminance(vec3 c) { return dot(c, vec3(0.2126, 0.7152, 0.0722)); }

// A PCG hash (O'Neill 2014) of v.
uint hash(uint v) {
    v = v * 747796405u + 2891336453u;
    v = ((v >> ((v >> 28u) + 4u)) ^ v) * 277803737u;
    return (v >> 22u) ^ v;
}

// A pixel's uniform number in [0, 1) for the choice of its tests (a PCG hash of the pixel and,
// cached, the frame).
float pixelRandom(ivec2 pixel, uint frameIndex) {
    return float(hash(uint(pixel.x) * 1973u + uint(pixel.y) * 9277u + frameIndex * 26699u) >> 8) /
           16777216.0;
}

// The flux's list, loaded once per group (every group's pixels gather from all of it): its
// position and probability; its flux and normal (octahedral); its texel (x + y * 65536).
shared vec4 listPosition[FLUX_VPLS];
shared vec4 listFlux[FLUX_VPLS];
shared uint listTexel[FLUX_VPLS];

// The group's run of FLUX_VPLS of the POOL drawn (consecutive points of the draw's sequence, so
// themselves evenly spread), from a place of its own: neighbouring groups gather different
// VPLs, and the filter, which reaches over groups, averages their errors instead of keeping
// one list's everywhere.
void loadList(bool cached) {
    uint group = gl_WorkGroupID.x + gl_WorkGroupID.y * 4099u;
    uint start = hash(group + (cached ? uint(frame.patternFrame) * 65521u : 0u)) % uint(POOL);
    for (int j = int(gl_LocalInvocationIndex); j < FLUX_VPLS; j += 64) {
        int k = int((start + uint(j)) % uint(POOL));
        vec4 row0 = texelFetch(vplList, ivec2(k, 0), 0);
        vec4 row1 = texelFetch(vplList, ivec2(k, 1), 0);
        vec4 row2 = texelFetch(vplList, ivec2(k, 2), 0);
        listPosition[j] = vec4(row0.xyz, row2.w);
        listFlux[j] = vec4(row2.rgb, uintBitsToFloat(packSnorm2x16(octahedralEncode(row1.xyz))));
        listTexel[j] = uint(row0.w) + uint(row1.w) * 65536u;
    }
    barrier();
}

// Each candidate's light before visibility (rgb; a: luminance), where its VPL lies and the
// normal of its surface there.
vec4 candidateLight[CANDIDATES];
vec3 candidatePosition[CANDIDATES];
vec3 candidateNormal[CANDIDATES];

void main() {
    loadPixelToWorld(); // pixel_to_world.glsl
    bool cached = constants.radialOffset >= 0.0;
    loadList(cached);
    int margin = interleavedFilterReach(RADIUS, INTERLEAVE);
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(pixel, ivec2(frame.viewport.xy)))) return;
    vec4 position = gbufferPosition(pixel);
    if (position.w == 0.0 || convergedAround(pixel, position.xyz, constants.cache, margin)) {
        imageStore(interleavedIndirect, pixel, SKIPPED);
        imageStore(interleavedDirectional, pixel, SKIPPED);
        return;
    }
    vec3 n = texelFetch(gbufferNormal, pixel, 0).xyz;
    vec3 p = position.xyz;
    int turn = cached ? int(fract(frame.patternFrame * 0.618034) * float(SUBSETS)) : 0;
    int subset = (vplSubset(pixel.x, pixel.y, INTERLEAVE) + turn) % SUBSETS;

    // The pattern around p's projection, as indirect_gather.glsl draws it.
    vec4 clip = frame.lightViewProjection * vec4(p, 1.0);
    vec2 center = clip.w > 0.0 ? clip.xy / clip.w * 0.5 + 0.5 : vec2(0.5);
    VplPattern pattern =
        vplPattern(clamp(center, vec2(0.0), vec2(1.0)), constants.radius * constants.scale);
    float size = float(MAP_SIZE);
    float rotation = pixelRotation(pixel) + constants.rotation;
    float stratum = radialOffset(constants.radialOffset, 0.5);
    int patternCount = vplSubsetSize(subset, VPLS, INTERLEAVE);
    int fluxCount = vplSubsetSize(subset, FLUX_VPLS, INTERLEAVE);
    float totalFlux = texelFetch(vplList, ivec2(POOL, 0), 0).r;
    // A VPL of one subset of k^2 stands for k^2 texels: its footprint is k texels wide, at its
    // distance from the light (squared, over that distance squared).
    float footprintScale = pow(2.0 * frame.lightFrustum.z / (2.0 * size) * float(INTERLEAVE), 2.0);

    vec4 directional = vec4(0.0);
    float lightSum = 0.0;
    int lit = 0;
    for (int c = 0; c < patternCount + fluxCount; ++c) {
        ivec2 texel;
        vec3 q, nq, flux;
        float r, pFlux;
        if (c < patternCount) {
            int i = vplOfSubset(subset, c, INTERLEAVE);
            vec2 uv = vplPatternPoint(pattern, i, VPLS, stratum, rotation, r);
            candidateLight[c] = vec4(0.0);
            if (any(lessThan(uv, vec2(0.0))) || any(greaterThanEqual(uv, vec2(1.0)))) continue;
            texel = ivec2(uv * size);
            vec4 stored = texelFetch(vplPosition, texel, 0);
            if (stored.w == 0.0) continue;
            q = stored.xyz;
            nq = texelFetch(vplNormal, texel, 0).xyz;
            flux = texelFetch(vplFlux, texel, 0).rgb;
            pFlux = totalFlux > 0.0 ? luminance(flux) / totalFlux : 0.0;
            if (pFlux <= 0.0) continue;
        } else {
            int j = vplOfSubset(subset, c - patternCount, INTERLEAVE);
            vec4 stored = listPosition[j];
            candidateLight[c] = vec4(0.0);
            if (stored.w <= 0.0) continue;
            q = stored.xyz;
            pFlux = stored.w;
            flux = listFlux[j].rgb;
            nq = octahedralDecode(unpackSnorm2x16(floatBitsToUint(listFlux[j].w)));
            uint packed = listTexel[j];
            r = length((vec2(packed & 0xffffu, packed >> 16) + 0.5) / size - pattern.center);
        }
        vec3 toVpl = q - p;
        float distance2 = dot(toVpl, toVpl);
        vec3 D = toVpl * inversesqrt(max(distance2, tinyLength2()));
        float cosQ = -dot(nq, D);
        if (cosQ <= 0.0) continue; // p lies behind the VPL's surface
        // Both densities at this texel, a texel 1 / size^2 of the map's uv.
        float pPattern = vplPatternDensity(pattern, r, size) / (size * size);
        float weight = 1.0 / (float(patternCount) * pPattern + float(fluxCount) * pFlux);
        // The distance clamped to the VPL's footprint, as indirect_gather.glsl's.
        vec3 fromLight = q - frame.lightPosition.xyz;
        float d2 = max(distance2, dot(fromLight, fromLight) * footprintScale);
        // Irradiance / pi, as the other methods': the VPL's light before p's cosine (for the
        // directional sums), then with it.
        float toP = cosQ * weight / (PI * PI * d2);
        float lightLuminance = pFlux * totalFlux * toP;
        directional += lightLuminance * vec4(1.0, D);
        float cosP = max(dot(n, D), 0.0);
        candidateLight[c] = vec4(flux * (toP * cosP), lightLuminance * cosP);
        candidatePosition[c] = q;
        candidateNormal[c] = nq;
        lightSum += candidateLight[c].a;
        if (cosP > 0.0) ++lit;
    }

    // Which VPLs are tested, and each one's weight: every one that brings light when there are
    // few enough, else TESTS draws by systematic sampling of their light (the k-th at
    // (k + u) L / TESTS along the running sum), a VPL drawn n times weighted n L / (TESTS L_i).
    // The tests run in a loop of their own, so that neighbouring pixels (SIMD lanes) run them
    // together whichever VPLs they chose.
    int chosen[MAX_TESTS];
    float factor[MAX_TESTS];
    int tests = 0;
    bool all = VISIBILITY == 0 || TESTS == 0 || lit <= TESTS;
    float step = lightSum / float(max(TESTS, 1));
    float u = pixelRandom(pixel, cached ? uint(frame.patternFrame) : 0u);
    float before = 0.0;
    vec3 irradiance = vec3(0.0);
    for (int c = 0; c < patternCount + fluxCount; ++c) {
        float l = candidateLight[c].a;
        if (l <= 0.0) continue;
        float draws = all ? 1.0 : ceil((before + l) / step - u) - ceil(before / step - u);
        before += l;
        if (draws <= 0.0) continue;
        float weight = all ? 1.0 : draws * step / l;
        if (VISIBILITY == 0) {
            irradiance += candidateLight[c].rgb;
        } else if (tests < MAX_TESTS) {
            chosen[tests] = c;
            factor[tests++] = weight;
        }
    }
    for (int t = 0; t < tests; ++t)
        if (vplVisible(p, candidatePosition[chosen[t]], candidateNormal[chosen[t]]))
            irradiance += candidateLight[chosen[t]].rgb * factor[t];
    imageStore(interleavedIndirect, pixel, vec4(irradiance, 1.0));
    imageStore(interleavedDirectional, pixel, directional);
}
