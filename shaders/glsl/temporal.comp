#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_vote : require
// The temporal cache (thesis 3.1.2) of every cached effect, in one pass: each pixel's surface is
// found once in last frame's image (the reprojection pass's, unpacked once here), and each
// effect's value of this frame V_t, computed with a turned and scaled sampling pattern, is
// blended with its reprojected history V_{t-1}, by the effect's own constants (its rule, tile,
// blur budget, motion test) and the same code for all. Up to TEMPORAL_EFFECT_SLOTS effects a
// dispatch (shared_cache.h), in slots 0..EFFECTS-1 (renderer/passes/temporal_pass.cpp).
// Thesis rule: confidence = 1 - saturate(|V_{t-1} - V_t|) / (1 + bias) (4),
// V = confidence V_{t-1} + (1 - confidence) V_t (5). Running mean (the principled
// alternative): V = H + (V_t - H) / (n + 1), with H the history clamped to the spread of this
// frame's values around the pixel. A pixel the effect skipped (converged) keeps its history; a
// disoccluded pixel starts over from V_t. The refresh tile was computed although converged, and
// its fresh value is blended in like any other, which pulls back what the bilinear resampling
// of the history has blurred without restarting the tile's accumulation (where nothing blurred
// it, on a still camera, the history is kept as it is). Beyond the thesis, the
// history's alpha holds that blur (squared pixels), and the effect's budget bounds it: a moving
// camera's history loses weight, and converged pixels are computed again, before their blur
// exceeds it (a budget of 0: computed anew while the camera moves, accumulated while still).
#include "shared.h"
#include "common.glsl"
// temporal.glsl's helpers for a pass that binds one effect's counts are not this pass's.
#define SSGI_TEMPORAL_PASS

layout(local_size_x = 8, local_size_y = 8) in;
// How many slots hold an effect this dispatch (1..TEMPORAL_EFFECT_SLOTS); the rest are bound to
// stand-ins, never read, whose one texel is written 0 so that no image holds undefined memory.
layout(constant_id = 0) const int EFFECTS = 1;
// Bit k set: slot k's history is a scalar effect's (the shadow, the AO): rg16f, its value in r
// and its blur in g; clear: rgba16f, the value in rgb and the blur in alpha (EffectCache::scalar).
layout(constant_id = 1) const int SCALAR_HISTORIES = 0;
// Once the camera holds still, a converged history that motion resampled with more than
// RESTART_BLUR (squared pixels) starts its accumulation over; one with more than
// REACCUMULATE_BLUR keeps being computed and blended until its blur falls below it. After a
// restart a history's blur falls to 2 / (n + 1) of what it was within the n = 36 frames to
// convergence, so a budget up to 4 px^2 restarts once.
const float RESTART_BLUR = 0.25;
const float REACCUMULATE_BLUR = 0.05;
// Texels that differ by at most this fraction of the largest (or of AGREE_FLOOR, where all are
// about 0) are one value to resampling (historyAt).
const float AGREE_TOLERANCE = 1.0 / 2048.0;
const float AGREE_FLOOR = 1e-4;
// The most blur one frame of motion adds (a filter's spread, squared pixels).
const float MOTION_BLUR_STEP = 0.5;
// A converged value that agreeing texels carried while the camera moved (historyAt) was computed
// at the texels' points, not at its own: it is stored with its blur as -(blur + CARRIED), and
// computed again once the camera holds still.
const float CARRIED = 1.0;

layout(set = 0, binding = 0, std140) uniform FrameBlock { FrameUniforms frame; };
layout(set = 0, binding = 1) uniform sampler2D gbufferViewDepth;
layout(set = 0, binding = 2) uniform sampler2D historyViewDepth;
layout(set = 0, binding = 3) uniform usampler2D reprojection;
// Per slot k: this frame's value (wasSkipped: converged, not computed), last frame's history
// and counts, and this frame's history (rgba16f or rg16f) and counts (packCount).
#define EFFECT_SLOT(k, first)                                                                     \
    layout(set = 0, binding = first) uniform sampler2D current##k;                                \
    layout(set = 0, binding = first + 1) uniform sampler2D historyValue##k;                       \
    layout(set = 0, binding = first + 2) uniform sampler2D historyCount##k;                       \
    layout(set = 0, binding = first + 3) uniform writeonly image2D newValue##k;                   \
    layout(set = 0, binding = first + 4) uniform writeonly image2D newCount##k;
EFFECT_SLOT(0, 4)
EFFECT_SLOT(1, 9)
EFFECT_SLOT(2, 14)
EFFECT_SLOT(3, 19)
layout(set = 0, binding = 24, std430) readonly buffer TemporalBlock { TemporalEffects temporal; };

#include "gbuffer_position.glsl"
#include "screen_space.glsl"
#include "temporal.glsl"

// Whether two values are one to resampling: they differ by at most AGREE_TOLERANCE of the
// larger (or of AGREE_FLOOR, where both are about 0).
bool agreesWith(vec3 a, vec3 b) {
    vec3 larger = max(abs(a), abs(b));
    float largest = max(max(larger.r, larger.g), max(larger.b, AGREE_FLOOR));
    return all(lessThanEqual(abs(a - b), vec3(AGREE_TOLERANCE * largest)));
}

// A history texel as value (rgb) and blur (a), whichever layout holds it, and whether
// agreement carried it (CARRIED); and the other way.
vec4 historyTexel(sampler2D historyValue, bool scalar, ivec2 q, inout bool carried) {
    vec4 t = texelFetch(historyValue, q, 0);
    t = scalar ? vec4(t.rrr, t.g) : t;
    if (t.a < 0.0) {
        carried = true;
        t.a = -t.a - CARRIED;
    }
    return t;
}
vec4 historyStored(bool scalar, vec3 value, float blur, bool carried) {
    if (carried) blur = -(blur + CARRIED);
    return scalar ? vec4(value.r, blur, 0.0, 0.0) : vec4(value, blur);
}

// The history at the reprojected point, filtered bilinearly over the four texels around it that
// hold the same surface (their world positions pass the reprojection test), so that across a
// depth edge the other side's value does not bleed in; the nearest texel passed already.
// Alpha: the texels' resampling blur (stored in the history's alpha), in squared pixels.
// `spread`: the blur this resampling adds, the spread of the filter around the point,
// sum w_i |x_i - x|^2. Each frame of motion adds up to half a pixel^2; a still camera samples
// texel centres and adds nothing. The distances are in this frame's pixels: after a resize the
// history's texels are of another size (Renderer::continueFrom), and what resampling them blurs
// counts the same. `agree`: a view-independent effect's four texels all hold the surface and
// agree to within AGREE_TOLERANCE of the largest; any filter over them gives the same value, so
// resampling them adds no blur (a lit or umbral region of the shadow), whatever the spread.
// `carried`: a texel it read holds a value agreement carried (CARRIED).
vec4 historyAt(CacheConstants cache, bool scalar, sampler2D historyValue, sampler2D historyCount,
               Reprojection r, out float spread, out bool agree, out bool carried) {
    carried = false;
    vec2 size = vec2(textureSize(historyValue, 0));
    vec2 toPixels = frame.viewport.xy / size;
    vec2 texel = r.uv * size - 0.5;
    ivec2 base = ivec2(floor(texel));
    vec2 f = texel - vec2(base);
    ivec2 last = ivec2(size) - 1;
    vec4 sum = vec4(0.0);
    float weights = 0.0;
    spread = 0.0;
    vec3 low = vec3(1e30), high = vec3(-1e30);
    int texels = 0;
    for (int i = 0; i < 4; ++i) {
        ivec2 offset = ivec2(i & 1, i >> 1);
        ivec2 q = clamp(base + offset, ivec2(0), last);
        if ((r.footprint & (1 << i)) == 0 || texelFetch(historyCount, q, 0).r == 0.0)
            continue; // 0: holds nothing (packCount)
        float w = (offset.x == 1 ? f.x : 1.0 - f.x) * (offset.y == 1 ? f.y : 1.0 - f.y);
        vec2 d = (vec2(offset) - f) * toPixels;
        vec4 v = historyTexel(historyValue, scalar, q, carried);
        sum += w * v;
        spread += w * dot(d, d);
        weights += w;
        low = min(low, v.rgb);
        high = max(high, v.rgb);
        ++texels;
    }
    agree = (cache.reprojection & REUSE_AGREEING) != 0 && texels == 4 &&
            agreesWith(low, high);
    vec4 v;
    if (weights > 1e-6) {
        v = sum / weights;
        spread /= weights;
    } else { // no texel around passed: the one that did (the nearest, or one beside it)
        vec2 d = (vec2(r.texel) + 0.5 - r.uv * size) * toPixels;
        spread = dot(d, d);
        v = historyTexel(historyValue, scalar, r.texel, carried);
    }
    // Offsets below a thirtieth of a pixel are rounding (a still camera): no blur, and the
    // texel itself, unfiltered, so that a still camera carries its history over exactly (the
    // rounding's tiny weights on the neighbours changed a half float's last digit now and then).
    if (spread < 1e-3) {
        spread = 0.0;
        v = historyTexel(historyValue, scalar, r.texel, carried);
    }
    return v;
}

// One effect's history and counts at this pixel this frame.
struct Carried {
    vec3 value;
    float blur;
    float count;
    bool due;
    bool carried; // by agreeing texels, not computed at its point since (CARRIED)
};

// One effect's value of this frame blended into its history at a pixel whose surface the
// reprojection pass found at `s` (world position `world`), by the effect's constants `cache`.
Carried carry(CacheConstants cache, bool scalar, sampler2D current, sampler2D historyValue,
              sampler2D historyCount, ivec2 pixel, vec3 world, SurfaceReprojection s) {
    vec4 now = effectValue(current, scalar, pixel);
    float stored = s.found ? texelFetch(historyCount, s.texel, 0).r : 0.0;
    Reprojection r = reprojectInto(s, stored, world, cache);
    float spread = 0.0;
    bool agree = false, carried = false;
    vec4 history = r.valid ? historyAt(cache, scalar, historyValue, historyCount, r, spread, agree,
                                       carried)
                           : vec4(0.0);
    // Texels that agree say the value is one constant around the point, so that resampling them
    // loses nothing; a value computed here that differs from theirs shows it is not (a needle's
    // shadow falling between texel centres that are all lit), and the history is resampled
    // like any other, blur and all.
    if (agree && !wasSkipped(now)) agree = agreesWith(history.rgb, now.rgb);
    // The blur this frame's resampling added (the history's blur is its texels' plus that), and
    // what the next frame's will add if the camera moves as it did (or, from a still camera, as
    // far as one frame of motion can).
    float added = agree ? 0.0 : spread;
    history.a += added;
    float nextAdded = agree ? 0.0 : spread > 0.0 ? spread : MOTION_BLUR_STEP;
    // The first frame after a resize, whose history still has the old size: a colour history
    // (the indirect light, SSDO: smooth) keeps its weight through the one resampling, whatever
    // its budget; a scalar one keeps it within its budget only, and the sharp shadow (budget 0)
    // starts over: a shadow resampled to another size is wrong along every edge, and a still
    // camera would keep it (docs/temporal-cache.md, "Resize", measures it).
    bool resized = !scalar &&
                   any(notEqual(textureSize(historyValue, 0), ivec2(frame.viewport.xy)));
    float budget = cache.blurBudget;
    // Reused while the camera moves, a pixel's value is computed again once its blur passes a
    // limit between half the budget and the budget, drawn per workgroup, so that the pixels that
    // started together (after a cut) do not all fall due in the same frame. An exact effect's
    // one computation is converged already: it is reused by its budget alone.
    bool reuseWhileMoving = (cache.reprojection & REUSE_WHILE_MOVING) != 0 && !exactEffect(cache);
    float limit = budget;
    if (reuseWhileMoving) limit *= 0.5 + 0.25 * pixelRotation(ivec2(gl_WorkGroupID.xy)) / PI;
    float rotations = float(cache.rotations);
    vec3 value;
    float count, blur = 0.0;
    // An exact effect (one rotation: no noise to average, CachedEffect::exact) takes a value
    // computed again whole.
    bool exact = exactEffect(cache);
    if (wasSkipped(now)) { // converged: its cache is the value
        value = history.rgb;
        count = r.count;
        blur = history.a;
        // Resampled past its budget (its texels no longer agree), the value counts as one
        // sample: computed again next frame, it is soon replaced, moving or still. So does a
        // value agreement carried, once the camera holds still: the texels it came from agreed,
        // but a needle's shadow may fall between their points and on this one.
        if ((blur > budget && !resized) || (carried && spread == 0.0))
            count = exact ? 0.0 : min(count, 1.0);
    } else if (!r.valid || exact) {
        value = now.rgb;
        count = 1.0;
    } else {
        // The weight of this frame's value, by the rule...
        float fresh;
        if (cache.runningMean == 0) {
            float confidence = 1.0 - clamp(length(history.rgb - now.rgb), 0.0, 1.0) /
                                         (1.0 + cache.confidenceBias);
            fresh = 1.0 - confidence;
        } else {
            // Where the camera moved, the history is clamped to this frame's values around the
            // pixel (every other pixel, so that a half-resolution effect's upsampled neighbours
            // do not all repeat one sample), widened to their mean +- 2.5 standard deviations: a
            // few samples a frame are noisy, and a box of their bare range would drag the
            // history towards that noise. A still camera reprojects every pixel onto itself and
            // its history cannot be stale (a moved light or object restarts what it changes), so
            // there the clamp, which a noisy frame's neighbourhood makes too tight, is left out.
            // Nor is a converged pixel computed again (the refresh tile).
            if (r.count < rotations && spread > 0.0) {
                vec3 sum = vec3(0.0), sumSquares = vec3(0.0);
                float n = 0.0;
                for (int y = -1; y <= 1; ++y)
                    for (int x = -1; x <= 1; ++x) {
                        ivec2 q = clamp(pixel + 2 * ivec2(x, y), ivec2(0),
                                        ivec2(frame.viewport.xy) - 1);
                        vec4 neighbour = effectValue(current, scalar, q);
                        if (neighbour.a < 0.5) continue;
                        sum += neighbour.rgb;
                        sumSquares += neighbour.rgb * neighbour.rgb;
                        n += 1.0;
                    }
                vec3 mean = sum / n;
                vec3 deviation = sqrt(max(sumSquares / n - mean * mean, vec3(0.0)));
                history.rgb = clamp(history.rgb, mean - 2.5 * deviation, mean + 2.5 * deviation);
            }
            fresh = 1.0 / (r.count + 1.0);
        }
        count = r.count + 1.0;
        // Re-convergence after motion: once the camera holds still (spread 0), a history that
        // motion resampled (and, with the running mean, clamped to a moving frame's noisy
        // neighbourhood) starts its accumulation over, keeping what it holds as one sample, so
        // that it settles where a fresh start does; while it still carries blur, each frame
        // weighs at least as in a running mean (the confidence rule alone would keep it).
        if (spread == 0.0 && (history.a > RESTART_BLUR || carried) &&
            r.count >= rotations - 1.0) {
            fresh = 0.5;
            count = 2.0;
        } else if (spread == 0.0 && history.a > 0.0) {
            fresh = max(fresh, 1.0 / (r.count + 1.0));
        } else if (spread == 0.0 && r.count >= rotations) {
            // The refresh tile on a still camera, over a converged history that no motion
            // resampled: it holds `rotations` frames at exactly this pixel, and the refresh, which
            // exists to pull back resampling blur (thesis ch. 4), has none to pull back. Blending
            // one noisy frame in there would be all the flicker of a still camera, so the history
            // is kept as it is.
            fresh = 0.0;
            count = r.count;
        }
        // ...and, while the camera moves, at least enough that the blended value's blur stays
        // within the budget. Where that cuts the history's weight, the count becomes the blend's
        // effective number of samples, 1 / ((1 - w)^2 / n + w^2), so the pixel accumulates
        // again before it is reused. Not on a still camera, whose leftover blur the
        // re-convergence above takes away, nor over a colour history's resize (above): with a
        // budget of 0 either would have thrown the history out.
        // Reused while moving, a value computed again takes the blur down to half its limit, so
        // that it is reused for a while before it is due again.
        float target = reuseWhileMoving ? 0.5 * limit : budget;
        if (spread > 0.0 && !resized && (1.0 - fresh) * history.a > target) {
            fresh = 1.0 - target / history.a;
            count = min(count, 1.0 / ((1.0 - fresh) * (1.0 - fresh) / max(r.count, 1.0) +
                                      fresh * fresh));
        }
        value = mix(history.rgb, now.rgb, fresh);
        blur = (1.0 - fresh) * history.a;
    }
    // A value that one more frame of this motion would take past the budget is not reused then:
    // its count stays below convergence, so the effect computes it again; so is a converged
    // value motion blurred, once the camera holds still, so that it accumulates again.
    if (blur + added > budget && count >= rotations) count = rotations - 1.0;
    // Reused while the camera moves, a value whose blur one more frame of this motion would take
    // past its limit is due: computed the next frame. The pixels the device runs together (a
    // subgroup: 8 on lavapipe, 32 on NVIDIA) fall due together: a subgroup in which one pixel
    // computes costs what all of them computing does.
    bool due = subgroupAny(reuseWhileMoving && blur + nextAdded > limit);
    if (spread == 0.0 && blur > REACCUMULATE_BLUR && count >= rotations) count = rotations - 1.0;
    if (blur < 1e-3) blur = 0.0; // below a thirtieth of a pixel: gone
    // A count stays at least 1 (0 is a pixel that holds nothing). An exact effect's one rotation
    // would make any count converged: there 0 has the pixel computed again next frame, and
    // EXACT_BLURRED marks a value that resampling has blurred, reused while the camera moves and
    // computed again once it holds still (temporal.glsl convergedAround).
    if (exact)
        count = count < rotations ? 0.0 : blur > REACCUMULATE_BLUR ? EXACT_BLURRED : 1.0;
    else
        count = max(min(count, rotations), 1.0);
    // Kept while the camera moves by agreement alone, the value is not this point's yet.
    bool carriedOn = wasSkipped(now) && spread > 0.0 && (agree || carried) && count >= 1.0;
    return Carried(value, blur, count, due, carriedOn);
}

void main() {
    loadPixelToWorld(); // pixel_to_world.glsl
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(pixel, ivec2(frame.viewport.xy)))) return;
    vec4 position = gbufferPosition(pixel);
    // Nothing drawn here: each effect's value as it is, holding nothing.
    bool background = position.w == 0.0;
    SurfaceReprojection s = SurfaceReprojection(false, vec2(0.0), ivec2(0), 0);
    if (!background) s = unpackReprojection(texelFetch(reprojection, pixel, 0).x, position.xyz);
#define CARRY_SLOT(k)                                                                             \
    if (EFFECTS > k) {                                                                            \
        bool scalar = (SCALAR_HISTORIES & (1 << k)) != 0;                                         \
        Carried c = Carried(texelFetch(current##k, pixel, 0).rgb, 0.0, 0.0, false, false);        \
        if (!background)                                                                          \
            c = carry(temporal.effects[k], scalar, current##k, historyValue##k, historyCount##k, pixel,    \
                      position.xyz, s);                                                           \
        imageStore(newValue##k, pixel, historyStored(scalar, c.value, c.blur, c.carried));        \
        imageStore(newCount##k, pixel, vec4(packCount(c.count, c.due)));                          \
    } else if (pixel == ivec2(0)) {                                                               \
        imageStore(newValue##k, pixel, vec4(0.0));                                                \
        imageStore(newCount##k, pixel, vec4(0.0));                                                \
    }
    CARRY_SLOT(0)
    CARRY_SLOT(1)
    CARRY_SLOT(2)
    CARRY_SLOT(3)
}
