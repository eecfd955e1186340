// What restarts a cached history (a moved light or object) and what carries it over (a resize).
#include "cache/cache.h"
#include "passes/pass_setup.h"

#include <glm/gtc/packing.hpp>

#include <algorithm>
#include <cstring>

namespace ssgi {

void restartCache(graph::FrameGraph& graph, const EffectCache& cache) {
    graph.resetHistory(cache.value);
    graph.resetHistory(cache.count);
}

void carryCaches(PassSetup& from, PassSetup& to) {
    if (!from.viewDepthHistory || !to.viewDepthHistory) return;
    // After its last frame every pair of `from` has swapped: what it wrote is the previous side.
    using graph::FrameGraph;
    auto last = [&from](uint32_t history) {
        return from.graph.readTexels(FrameGraph::previous(history));
    };
    bool carried = false;
    for (const EffectCache& old : from.caches) {
        if (!from.graph.hasHistory(old.value)) continue;
        for (const EffectCache& cache : to.caches) {
            if (cache.name != old.name) continue;
            to.graph.carryHistory(cache.value, from.size, last(old.value));
            // Each pixel's history counts as one sample (rotation count 1): screen-space effects
            // converge to another value at another size (their samples snap to other pixels),
            // and a history converged at the old size would hold the new one off for dozens of
            // frames (docs/temporal-cache.md, "Resize"). The shadow, which allows no blur, starts
            // over; the others blend the new frames into the resampled image.
            std::vector<uint8_t> count = last(old.count);
            for (size_t i = 0; i + 2 <= count.size(); i += 2) { // R16F
                uint16_t n = 0;
                std::memcpy(&n, &count[i], 2);
                n = glm::packHalf1x16(std::min(glm::unpackHalf1x16(n), 1.0f));
                std::memcpy(&count[i], &n, 2);
            }
            to.graph.carryHistory(cache.count, from.size, count);
            carried = true;
        }
    }
    if (carried)
        to.graph.carryHistory(*to.viewDepthHistory, from.size, last(*from.viewDepthHistory));
}

} // namespace ssgi
