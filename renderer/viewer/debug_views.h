// The views of the temporal cache that the composite does not draw, made on the CPU from what
// the renderer's last frame wrote: per cached effect, its history confidence (rotation count of
// the pixel over the count that makes it converged), the disocclusion mask (pixels whose history
// was rejected this frame), the converged mask, and the tile refreshed this frame.
#pragma once

#include "renderer.h"

#include <cstdint>
#include <string>
#include <vector>

namespace ssgi::viewer {

enum class CacheView { Confidence, Disocclusion, Converged, RefreshedTile };

struct CacheViewInfo {
    CacheView view;
    const char* key; // for the command line
    const char* name;
    const char* meaning;
};
const std::vector<CacheViewInfo>& cacheViews();

// RGBA8 pixels of the renderer's size (rows top to bottom). The masks and the tile are drawn
// over a dimmed grey copy of the final image so that the scene stays recognisable.
std::vector<uint8_t> makeCacheView(Renderer& renderer, CacheView view, const std::string& effect,
                                   uint32_t rotations);

// Over the pixels with geometry: the largest rotation count of the effect's history, and the
// fraction of pixels at that count or beyond `rotations` (converged). For the report and tests.
struct CacheSummary {
    float maxCount = 0.0f, meanCount = 0.0f, convergedFraction = 0.0f;
};
CacheSummary summariseCache(Renderer& renderer, const std::string& effect, uint32_t rotations);

} // namespace ssgi::viewer
