#include "viewer/debug_views.h"

#include <algorithm>
#include <cmath>

namespace ssgi::viewer {

const std::vector<CacheViewInfo>& cacheViews() {
    static const std::vector<CacheViewInfo> views = {
        {CacheView::Confidence, "confidence", "history confidence",
         "rotations accumulated / rotations to converge (black: none, white: converged)"},
        {CacheView::Disocclusion, "disocclusion", "disocclusion mask",
         "red: history rejected this frame (reprojection test failed, or none yet)"},
        {CacheView::Converged, "converged", "converged mask",
         "green: converged, the effect reuses its cache"},
        {CacheView::RefreshedTile, "refreshed-tile", "refreshed tile",
         "yellow: the tile computed anew this frame"},
    };
    return views;
}

namespace {

uint8_t byte(float v) {
    return uint8_t(std::lround(std::clamp(v, 0.0f, 1.0f) * 255.0f));
}

} // namespace

std::vector<uint8_t> makeCacheView(Renderer& renderer, CacheView view, const std::string& effect,
                                   uint32_t rotations) {
    const VkExtent2D size = renderer.size();
    const size_t count = size_t(size.width) * size.height;
    const std::vector<float> ldr = renderer.readImage("ldr");
    std::vector<float> meta;
    if (view != CacheView::RefreshedTile) meta = renderer.readImage(effect + ".meta");
    const VkRect2D tile = renderer.refreshedTile(effect);
    std::vector<uint8_t> out(count * 4, 255);
    for (size_t i = 0; i < count; ++i) {
        const float grey =
            0.45f * (0.2126f * ldr[4 * i] + 0.7152f * ldr[4 * i + 1] + 0.0722f * ldr[4 * i + 2]);
        glm::vec3 c(grey);
        // The temporal pass writes a count of at least 1 wherever there is geometry, 0 elsewhere.
        const float rotationsDone = meta.empty() ? 0.0f : meta[4 * i + 3];
        const bool geometry = rotationsDone > 0.0f;
        switch (view) {
        case CacheView::Confidence:
            c = glm::vec3(rotationsDone / float(rotations));
            break;
        case CacheView::Disocclusion:
            if (geometry && rotationsDone <= 1.0f) c = glm::vec3(0.9f, 0.1f, 0.1f);
            break;
        case CacheView::Converged:
            if (rotationsDone >= float(rotations)) c = glm::vec3(0.15f, 0.8f, 0.2f);
            break;
        case CacheView::RefreshedTile: {
            const int32_t x = int32_t(i % size.width), y = int32_t(i / size.width);
            if (x >= tile.offset.x && y >= tile.offset.y &&
                x < tile.offset.x + int32_t(tile.extent.width) &&
                y < tile.offset.y + int32_t(tile.extent.height))
                c = glm::mix(c, glm::vec3(1.0f, 0.85f, 0.1f), 0.7f);
            break;
        }
        }
        out[4 * i] = byte(c.r);
        out[4 * i + 1] = byte(c.g);
        out[4 * i + 2] = byte(c.b);
    }
    return out;
}

CacheSummary summariseCache(Renderer& renderer, const std::string& effect, uint32_t rotations) {
    const std::vector<float> meta = renderer.readImage(effect + ".meta");
    CacheSummary s;
    size_t covered = 0, converged = 0;
    double sum = 0.0;
    for (size_t i = 0; i + 3 < meta.size(); i += 4) {
        const float n = meta[i + 3];
        if (n <= 0.0f) continue; // no geometry: the temporal pass writes zero
        ++covered;
        sum += n;
        s.maxCount = std::max(s.maxCount, n);
        if (n >= float(rotations)) ++converged;
    }
    if (covered > 0) {
        s.meanCount = float(sum / double(covered));
        s.convergedFraction = float(converged) / float(covered);
    }
    return s;
}

} // namespace ssgi::viewer
