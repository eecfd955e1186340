#version 460
#extension GL_GOOGLE_include_directive : require
// The VPLs of indirect_method 2, in two stages.
// STAGE 0 (`indirect.flux`, one invocation per VPL-map texel, an 8 x 8 group per 8 x 8 texels):
//   clusters CLUSTER x CLUSTER texels of the RSM into one VPL of the VPL map: its flux the
//   texels' sum, its position and normal the means of its middle texels' weighted by their
//   flux's luminance.
//   A coarser map holds the same light in far fewer texels (1/16 at CLUSTER 4), so that the
//   gather's scattered reads stay in the caches; the distance clamp is as wide as a VPL anyway.
//   It then sums the VPLs' luminance into levels 1-3 of a pyramid, in shared memory.
// STAGE 1 (`indirect.vpls`, one group): sums the levels above, to the 1 x 1 total, and draws
//   FLUX_VPLS VPLs with probability lum(flux_q) / (sum of lum(flux)) by hierarchical warping:
//   low-discrepancy points (the R2 sequence, moved each frame when cached) go down the pyramid,
//   at each level to the column and then the row their coordinates fall in, in proportion to
//   the children's sums, each coordinate rescaled into the part chosen; stratified points so
//   stay stratified in the flux. The list holds, per VPL, its position, normal, flux and
//   probability, and in its last column the total; the gather (indirect_importance.comp)
//   weighs each VPL by that probability, so that its estimate stays unbiased.
// Pyramid level l >= 1 (side paddedSize >> l) lies at (0, paddedSize - (paddedSize >> (l-1)))
// of `fluxPyramid`; level 0 is the VPL map's luminance, padded with zeros to paddedSize.
#include "shared.h"
#include "common.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(constant_id = 0) const int STAGE = 0;
layout(constant_id = 1) const int FLUX_VPLS = 2048; // drawn each frame: indirect_flux_pool
layout(constant_id = 2) const int CLUSTER = 4;      // RSM texels per VPL, per side

layout(set = 0, binding = 0, std140) uniform FrameBlock { FrameUniforms frame; };
layout(set = 0, binding = 1) uniform usampler2D rsmVpls; // rsm_vpl.glsl
// The VPL map: position (w 1 where the VPL carries light), normal, flux.
layout(set = 0, binding = 2, rgba32f) uniform image2D vplPosition;
layout(set = 0, binding = 3, rgba32f) uniform image2D vplNormal;
layout(set = 0, binding = 4, rgba32f) uniform image2D vplFlux;
layout(set = 0, binding = 5, r32f) uniform coherent image2D fluxPyramid;
// FLUX_VPLS + 1 columns: row 0 (position, VPL-map texel x), row 1 (normal, texel y), row 2
// (flux, the VPL's probability); column FLUX_VPLS, row 0: the total luminance.
layout(set = 0, binding = 6, rgba32f) uniform writeonly image2D vplList;
layout(push_constant) uniform VplDrawBlock { VplDrawConstants constants; };

#include "rsm_vpl.glsl"

shared float sums[8][8];

float luminance(vec3 c) { return dot(c, vec3(0.2126, 0.7152, 0.0722)); }

ivec2 levelOrigin(int level) {
    return ivec2(0, constants.paddedSize - (constants.paddedSize >> (level - 1)));
}

// The luminance a texel of `level` sums (level 0: one VPL's; 0 beyond the VPL map).
float levelSum(int level, ivec2 texel) {
    if (level > 0) return imageLoad(fluxPyramid, levelOrigin(level) + texel).r;
    if (any(greaterThanEqual(texel, ivec2(constants.vplMapSize)))) return 0.0;
    return luminance(imageLoad(vplFlux, texel).rgb);
}

// One VPL from its CLUSTER x CLUSTER texels of the RSM; returns its flux's luminance. Its flux
// is every texel's; its place, the mean of the middle 2 x 2 texels' weighted by their flux's
// luminance (the block's centre on a plane, for a fraction of the reads), or the brightest
// texel's where the middle holds no light. The RSM holds no flux where it holds no surface.
float cluster(ivec2 vpl) {
    ivec2 corner = vpl * CLUSTER;
    ivec2 last = ivec2(constants.mapSize - 1);
    vec3 flux = vec3(0.0);
    float brightest = 0.0;
    ivec2 brightestTexel = corner;
    for (int y = 0; y < CLUSTER; ++y)
        for (int x = 0; x < CLUSTER; ++x) {
            ivec2 texel = corner + ivec2(x, y);
            bool inside = all(lessThanEqual(texel, last));
            vec3 f = inside ? rsmTexelFlux(texelFetch(rsmVpls, min(texel, last), 0)) : vec3(0.0);
            flux += f;
            if (luminance(f) > brightest) {
                brightest = luminance(f);
                brightestTexel = texel;
            }
        }
    vec3 position = vec3(0.0), normal = vec3(0.0);
    float weight = 0.0;
    ivec2 middle = corner + (CLUSTER - 1) / 2;
    for (int i = 0; i < 4; ++i) {
        ivec2 texel = min(middle + ivec2(i & 1, i >> 1), last);
        uvec4 vpl = texelFetch(rsmVpls, texel, 0);
        float w = luminance(rsmTexelFlux(vpl));
        position += w * rsmTexelPosition(texel, vpl);
        normal += w * rsmTexelNormal(vpl);
        weight += w;
    }
    if (weight == 0.0 && brightest > 0.0) {
        uvec4 vpl = texelFetch(rsmVpls, brightestTexel, 0);
        position = rsmTexelPosition(brightestTexel, vpl);
        normal = rsmTexelNormal(vpl);
        weight = 1.0;
    }
    bool lit = weight > 0.0 && length(normal) > 0.0;
    imageStore(vplPosition, vpl, lit ? vec4(position / weight, 1.0) : vec4(0.0));
    imageStore(vplNormal, vpl, lit ? vec4(normalize(normal), 0.0) : vec4(0.0));
    imageStore(vplFlux, vpl, lit ? vec4(flux, 1.0) : vec4(0.0));
    return lit ? luminance(flux) : 0.0;
}

// The pyramid's texels that no level holds (beside levels 2 and up, and its last row) set to
// 0, so that the whole image holds defined values (the stability suite reads every image for
// NaN and Inf); group (0, 0) does it when the VPL map is made.
void clearUnused() {
    int width = constants.paddedSize / 2;
    int invocation = int(gl_LocalInvocationIndex);
    for (int level = 2; level <= constants.levels; ++level) {
        int side = constants.paddedSize >> level;
        int columns = width - side;
        for (int i = invocation; i < columns * side; i += 64)
            imageStore(fluxPyramid, levelOrigin(level) + ivec2(side + i % columns, i / columns),
                       vec4(0.0));
    }
    for (int x = invocation; x < width; x += 64)
        imageStore(fluxPyramid, ivec2(x, constants.paddedSize - 1), vec4(0.0));
}

// The VPL map of one 8 x 8 tile, and the pyramid's levels 1-3 over it.
void clusterTile() {
    if (gl_WorkGroupID.xy == uvec2(0)) clearUnused();
    ivec2 local = ivec2(gl_LocalInvocationID.xy);
    ivec2 group = ivec2(gl_WorkGroupID.xy);
    ivec2 vpl = group * 8 + local;
    float value = all(lessThan(vpl, ivec2(constants.vplMapSize))) ? cluster(vpl) : 0.0;
    sums[local.y][local.x] = value;
    barrier();
    for (int level = 1, side = 4; level <= 3; ++level, side /= 2) {
        bool inside = all(lessThan(local, ivec2(side)));
        if (inside) {
            ivec2 c = 2 * local;
            value = sums[c.y][c.x] + sums[c.y][c.x + 1] + sums[c.y + 1][c.x] +
                    sums[c.y + 1][c.x + 1];
        }
        barrier();
        if (inside) {
            sums[local.y][local.x] = value;
            imageStore(fluxPyramid, levelOrigin(level) + group * side + local, vec4(value));
        }
        barrier();
    }
}

// Where point u falls in the flux: down from the total, at each level the column of the four
// children and then the row, in proportion to their sums. Returns the VPL map's texel.
ivec2 warp(vec2 u) {
    ivec2 node = ivec2(0);
    for (int level = constants.levels; level >= 1; --level) {
        ivec2 c = 2 * node;
        float s00 = levelSum(level - 1, c), s10 = levelSum(level - 1, c + ivec2(1, 0));
        float s01 = levelSum(level - 1, c + ivec2(0, 1)), s11 = levelSum(level - 1, c + ivec2(1));
        float left = s00 + s01, right = s10 + s11;
        float pLeft = left / max(left + right, 1e-37);
        int column = u.x < pLeft ? 0 : 1;
        u.x = column == 0 ? u.x / max(pLeft, 1e-37) : (u.x - pLeft) / max(1.0 - pLeft, 1e-37);
        float top = column == 0 ? s00 : s10, bottom = column == 0 ? s01 : s11;
        float pTop = top / max(top + bottom, 1e-37);
        int row = u.y < pTop ? 0 : 1;
        u.y = row == 0 ? u.y / max(pTop, 1e-37) : (u.y - pTop) / max(1.0 - pTop, 1e-37);
        u = clamp(u, vec2(0.0), vec2(0.99999994));
        node = c + ivec2(column, row);
    }
    return node;
}

void drawList() {
    int invocation = int(gl_LocalInvocationIndex);
    // The levels above the tiles', each from the one below, the whole group at once.
    for (int level = 4; level <= constants.levels; ++level) {
        int side = constants.paddedSize >> level;
        for (int i = invocation; i < side * side; i += 64) {
            ivec2 t = ivec2(i % side, i / side);
            float sum = levelSum(level - 1, 2 * t) + levelSum(level - 1, 2 * t + ivec2(1, 0)) +
                        levelSum(level - 1, 2 * t + ivec2(0, 1)) + levelSum(level - 1, 2 * t + 1);
            imageStore(fluxPyramid, levelOrigin(level) + t, vec4(sum));
        }
        memoryBarrierImage();
        barrier();
    }
    float total = levelSum(constants.levels, ivec2(0));
    if (invocation == 0) { // the last column's other rows hold nothing
        imageStore(vplList, ivec2(FLUX_VPLS, 0), vec4(total));
        imageStore(vplList, ivec2(FLUX_VPLS, 1), vec4(0.0));
        imageStore(vplList, ivec2(FLUX_VPLS, 2), vec4(0.0));
    }
    // Cached, the points move frame by frame (by two irrationals, so the shifts never repeat)
    // and the frames' lists together cover the flux; uncached, every frame draws the same.
    vec2 shift = constants.cached != 0 ? fract(frame.patternFrame * vec2(0.618034, 0.4142136))
                                       : vec2(0.0);
    for (int j = invocation; j < FLUX_VPLS; j += 64) {
        // The R2 sequence (Roberts 2018): the golden ratio's 2-D generalisation.
        vec2 u = fract(vec2(0.5) + float(j) * vec2(0.7548776662, 0.5698402910) + shift);
        ivec2 vpl = total > 0.0 ? warp(u) : ivec2(0);
        vec4 flux = imageLoad(vplFlux, vpl);
        float probability = total > 0.0 ? luminance(flux.rgb) / total : 0.0;
        imageStore(vplList, ivec2(j, 0), vec4(imageLoad(vplPosition, vpl).xyz, vpl.x));
        imageStore(vplList, ivec2(j, 1), vec4(imageLoad(vplNormal, vpl).xyz, vpl.y));
        imageStore(vplList, ivec2(j, 2), vec4(flux.rgb, probability));
    }
}

void main() {
    loadPixelToWorld(); // pixel_to_world.glsl
    if (STAGE == 0)
        clusterTile();
    else
        drawList();
}
