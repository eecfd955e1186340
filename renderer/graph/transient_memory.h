// Where the frame graph's transient images lie in memory. An image whose contents live within
// one frame needs its memory only from the first pass that uses it to the last; images whose
// lifetimes do not overlap can share memory (aliasing, as render graphs do: Granite, Frostbite's
// FrameGraph). A pure function over sizes and lifetimes, testable without a device
// (tests/test_graph.cpp); the graph binds the images where it says (frame_graph.cpp).
#pragma once

#include <vulkan/vulkan.h>

#include <optional>
#include <vector>

namespace ssgi::graph {

struct TransientImage {
    VkDeviceSize size = 0, alignment = 1;
    uint32_t memoryTypeBits = ~0u;
    uint32_t first = 0, last = 0; // the passes that use it first and last (inclusive)
};

struct TransientPlan {
    VkDeviceSize blockSize = 0;  // one block of device memory for every shared image
    uint32_t memoryTypeBits = 0; // the memory types every shared image accepts
    // Each image's offset in the block, or none: it gets memory of its own (a memory type the
    // others do not share).
    std::vector<std::optional<VkDeviceSize>> offsets;
};

// Places the largest images first, each at the lowest offset (aligned) where it overlaps no
// image already placed whose lifetime overlaps its own: two images share bytes only when one's
// last pass comes before the other's first.
TransientPlan planTransientMemory(const std::vector<TransientImage>& images);

// Whether two placed images share any byte of the block.
bool shareMemory(VkDeviceSize offsetA, VkDeviceSize sizeA, VkDeviceSize offsetB,
                 VkDeviceSize sizeB);

} // namespace ssgi::graph
