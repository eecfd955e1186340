// Tiled refresh (thesis ch. 4, after Nehab et al. 2007): the screen is divided into tiles and
// each frame one tile not yet refreshed in this round is chosen at random and computed anew,
// so that the blur of resampling the history each frame cannot build up anywhere.
#pragma once

#include <cstdint>
#include <random>
#include <vector>

namespace ssgi {

// A tile's pixels; the last column and row of tiles may be cut short by the image's edge.
struct TileRect {
    uint32_t x, y, width, height;
};

class TileRefresh {
public:
    TileRefresh(uint32_t width, uint32_t height, uint32_t tileSize, uint32_t seed);
    uint32_t tileCount() const { return uint32_t(order_.size()); }
    uint32_t tileSize() const { return tileSize_; }
    // The tile to refresh this frame; every tile once per round, in a new order each round.
    uint32_t next();
    // Where tile `index` lies (row-major tiles).
    TileRect rect(uint32_t index) const;

private:
    uint32_t width_, height_, tileSize_;
    std::vector<uint32_t> order_;
    size_t position_ = 0;
    std::mt19937 random_;
};

} // namespace ssgi
