#include "cache/tile_refresh.h"

#include <algorithm>
#include <numeric>

namespace ssgi {

TileRefresh::TileRefresh(uint32_t width, uint32_t height, uint32_t tileSize, uint32_t seed)
    : width_(width), height_(height), tileSize_(tileSize), random_(seed) {
    const uint32_t tilesX = (width + tileSize - 1) / tileSize;
    const uint32_t tilesY = (height + tileSize - 1) / tileSize;
    order_.resize(size_t(tilesX) * tilesY);
    std::iota(order_.begin(), order_.end(), 0u);
    position_ = order_.size(); // the first call starts a round
}

uint32_t TileRefresh::next() {
    if (position_ == order_.size()) {
        std::shuffle(order_.begin(), order_.end(), random_);
        position_ = 0;
    }
    return order_[position_++];
}

TileRect TileRefresh::rect(uint32_t index) const {
    const uint32_t tilesX = (width_ + tileSize_ - 1) / tileSize_;
    const uint32_t x = (index % tilesX) * tileSize_, y = (index / tilesX) * tileSize_;
    return {x, y, std::min(tileSize_, width_ - x), std::min(tileSize_, height_ - y)};
}

} // namespace ssgi
