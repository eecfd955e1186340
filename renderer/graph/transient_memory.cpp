#include "graph/transient_memory.h"

#include <algorithm>
#include <numeric>

namespace ssgi::graph {

bool shareMemory(VkDeviceSize offsetA, VkDeviceSize sizeA, VkDeviceSize offsetB,
                 VkDeviceSize sizeB) {
    return offsetA < offsetB + sizeB && offsetB < offsetA + sizeA;
}

TransientPlan planTransientMemory(const std::vector<TransientImage>& images) {
    TransientPlan plan;
    plan.offsets.assign(images.size(), std::nullopt);
    std::vector<size_t> order(images.size());
    std::iota(order.begin(), order.end(), size_t(0));
    std::stable_sort(order.begin(), order.end(),
                     [&](size_t a, size_t b) { return images[a].size > images[b].size; });
    plan.memoryTypeBits = ~0u;
    std::vector<size_t> placed;
    for (size_t i : order) {
        const TransientImage& image = images[i];
        const uint32_t types = plan.memoryTypeBits & image.memoryTypeBits;
        if (types == 0) continue; // memory of its own
        plan.memoryTypeBits = types;
        // The byte ranges taken, while this image lives, by images already placed.
        std::vector<std::pair<VkDeviceSize, VkDeviceSize>> taken;
        for (size_t j : placed)
            if (images[j].first <= image.last && image.first <= images[j].last)
                taken.push_back({*plan.offsets[j], *plan.offsets[j] + images[j].size});
        std::sort(taken.begin(), taken.end());
        const VkDeviceSize align = std::max<VkDeviceSize>(image.alignment, 1);
        VkDeviceSize offset = 0;
        for (const auto& [begin, end] : taken) {
            if (offset + image.size <= begin) break; // fits in the gap before this range
            offset = std::max(offset, (end + align - 1) / align * align);
        }
        plan.offsets[i] = offset;
        plan.blockSize = std::max(plan.blockSize, offset + image.size);
        placed.push_back(i);
    }
    if (placed.empty()) plan.memoryTypeBits = 0;
    return plan;
}

} // namespace ssgi::graph
