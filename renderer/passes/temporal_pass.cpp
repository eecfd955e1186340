// temporal: the temporal cache of every cached effect (thesis 3.1) in one compute pass: each
// pixel's reprojection (the reprojection pass's) is read once, and each effect's value of this
// frame is blended into its history by the effect's own constants (temporal.comp). The effects
// are those handed to it since the frame's last temporal pass (blendInTemporalPass), up to
// cache_temporal_slots of them a dispatch (TEMPORAL_EFFECT_SLOTS at most); with more, or fewer
// slots, one dispatch a group, named after its effects.
//   reads:  gbuffer.view_depth, last frame's gbuffer.view_depth, reprojection; per effect its
//           value of this frame (<effect>), last frame's <effect>.history and <effect>.count
//   writes: per effect this frame's <effect>.history and <effect>.count
#include "passes/cached_effect_pass.h"

#include <algorithm>
#include <cstring>

namespace ssgi {

namespace {

// One dispatch over `group` (at most TEMPORAL_EFFECT_SLOTS effects, slot k the k-th).
void addTemporalDispatch(FrameBuild& build, const GBuffer& gbuffer,
                         std::vector<WaitingEffect> group, const std::string& name) {
    using graph::FrameGraph;
    using graph::Use;
    const uint32_t viewDepths = *build.caches.viewDepthHistory;
    ComputePassDesc pass{name, "temporal.comp"};
    pass.images = {{"gbufferViewDepth", gbuffer.viewDepth, Use::Sampled},
                   {"historyViewDepth", FrameGraph::previous(viewDepths), Use::Sampled},
                   {"reprojection", build.caches.reprojection, Use::Sampled}};
    int scalarHistories = 0;
    for (uint32_t k = 0; k < TEMPORAL_EFFECT_SLOTS; ++k) {
        const std::string slot = std::to_string(k);
        if (k < group.size()) {
            const EffectCache& cache = *group[k].cache;
            if (cache.effect.scalar) scalarHistories |= 1 << k;
            pass.images.insert(
                pass.images.end(),
                {{"current" + slot, group[k].value, Use::Sampled},
                 {"historyValue" + slot, FrameGraph::previous(cache.valueHistory), Use::Sampled},
                 {"historyCount" + slot, FrameGraph::previous(cache.countHistory), Use::Sampled},
                 {"newValue" + slot, FrameGraph::current(cache.valueHistory), Use::StorageWrite},
                 {"newCount" + slot, FrameGraph::current(cache.countHistory), Use::StorageWrite}});
            continue;
        }
        // An empty slot (EFFECTS): any image the pass reads, and a texel of each format the
        // shader writes (0, so that nothing holds undefined memory), which nothing else touches.
        const VkImageUsageFlags usage = VK_IMAGE_USAGE_STORAGE_BIT;
        const std::string unused = name + ".unused" + slot;
        pass.images.insert(
            pass.images.end(),
            {{"current" + slot, gbuffer.viewDepth, Use::Sampled},
             {"historyValue" + slot, gbuffer.viewDepth, Use::Sampled},
             {"historyCount" + slot, gbuffer.viewDepth, Use::Sampled},
             {"newValue" + slot,
              build.graph.createImage(unused + "_value", VK_FORMAT_R16G16B16A16_SFLOAT, {1, 1},
                                      usage, /*persistent=*/true),
              Use::StorageWrite},
             {"newCount" + slot,
              build.graph.createImage(unused + "_count", kCountFormat, {1, 1}, usage,
                                      /*persistent=*/true),
              Use::StorageWrite}});
    }
    pass.uniforms = {
        {"TemporalBlock", build.storageBuffer(sizeof(shader::TemporalEffects)), /*storage=*/true}};
    pass.spec = {{{"EFFECTS", int(group.size())}, {"SCALAR_HISTORIES", scalarHistories}}};
    void* const constants = pass.uniforms.back().buffer.mapped; // the build owns the buffer
    addComputePass(build, std::move(pass),
                   [&build, group = std::move(group), constants](const ComputeRecorder& r) {
                       // The frame waits for the last one before it is recorded (Renderer), so
                       // the buffer is free to write.
                       shader::TemporalEffects effects{};
                       for (size_t k = 0; k < group.size(); ++k)
                           effects.effects[k] =
                               cacheConstants(build.settings, group[k].cache, r.frame());
                       std::memcpy(constants, &effects, sizeof(effects));
                       const VkExtent2D area = cacheDispatch(group[0].cache, r.frame(), build.size);
                       r.dispatch(area.width, area.height);
                   });
}

} // namespace

void addTemporalPass(FrameBuild& build, const GBuffer& gbuffer) {
    std::vector<WaitingEffect> waiting = std::move(build.caches.waiting);
    build.caches.waiting.clear();
    const size_t slots =
        std::clamp<size_t>(size_t(build.settings.cache_temporal_slots), 1, TEMPORAL_EFFECT_SLOTS);
    for (size_t first = 0; first < waiting.size(); first += slots) {
        const size_t end = std::min(first + slots, waiting.size());
        std::vector<WaitingEffect> group(waiting.begin() + first, waiting.begin() + end);
        // The frame's one dispatch is "temporal"; one of several, named by its effects.
        std::string name = "temporal";
        if (group.size() < waiting.size() || build.caches.temporalPasses > 0) {
            name.clear();
            for (const WaitingEffect& w : group)
                name += (name.empty() ? "" : "+") + w.cache->name();
            name += ".temporal";
        }
        addTemporalDispatch(build, gbuffer, std::move(group), name);
        ++build.caches.temporalPasses;
    }
}

} // namespace ssgi
