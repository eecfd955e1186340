// Where the frame graph's images get their memory, and what it holds: histories and persistent
// images their own; transient images one shared block, placed by planTransientMemory where
// their lifetimes within the frame do not overlap (transient_memory.h).
#include "graph/frame_graph.h"
#include "graph/transient_memory.h"

#include <algorithm>
#include <stdexcept>

namespace ssgi::graph {

void FrameGraph::keep(ImageRef ref) {
    if (allocated_) throw std::logic_error("FrameGraph::keep after the first frame");
    resources_[resolve(ref)].kept = true;
}

void FrameGraph::keepAll() {
    if (allocated_) throw std::logic_error("FrameGraph::keepAll after the first frame");
    keepAll_ = true;
}

void FrameGraph::allocateTransients() {
    if (allocated_) return;
    allocated_ = true;
    const uint32_t frameEnd = uint32_t(passes_.size());
    std::vector<uint32_t> ids; // the transient resources some pass uses
    std::vector<TransientImage> images;
    std::vector<uint32_t> first(resources_.size(), UINT32_MAX), last(resources_.size(), 0);
    for (uint32_t p = 0; p < passes_.size(); ++p)
        for (const ImageUse& use : passes_[p].uses) {
            if (use.image.kind != ImageRef::Kind::Plain) continue; // histories persist
            first[use.image.index] = std::min(first[use.image.index], p);
            last[use.image.index] = std::max(last[use.image.index], p);
        }
    for (uint32_t id = 0; id < resources_.size(); ++id) {
        Resource& r = resources_[id];
        if (!r.transient || r.image.memory) continue;
        if (first[id] == UINT32_MAX) { // no pass uses it: memory of its own
            vk::bindImage(ctx_, r.image,
                          vk::allocateDeviceMemory(ctx_, r.image.requirements.size,
                                                   r.image.requirements.memoryTypeBits),
                          0);
            continue;
        }
        ids.push_back(id);
        images.push_back({r.image.requirements.size, r.image.requirements.alignment,
                          r.image.requirements.memoryTypeBits, first[id],
                          r.kept || keepAll_ ? frameEnd : last[id]});
        r.firstPass = first[id];
    }
    const TransientPlan plan = planTransientMemory(images);
    if (plan.blockSize > 0)
        sharedBlock_ = vk::allocateDeviceMemory(ctx_, plan.blockSize, plan.memoryTypeBits);
    sharedBytes_ = plan.blockSize;
    for (size_t i = 0; i < ids.size(); ++i) {
        Resource& r = resources_[ids[i]];
        if (plan.offsets[i]) {
            vk::bindImage(ctx_, r.image, sharedBlock_, *plan.offsets[i]);
            r.image.ownsMemory = false;
            r.shared = true;
        } else {
            vk::bindImage(ctx_, r.image,
                          vk::allocateDeviceMemory(ctx_, r.image.requirements.size,
                                                   r.image.requirements.memoryTypeBits),
                          0);
        }
    }
    for (size_t i = 0; i < ids.size(); ++i)
        for (size_t j = 0; j < ids.size(); ++j)
            if (i != j && plan.offsets[i] && plan.offsets[j] &&
                shareMemory(*plan.offsets[i], images[i].size, *plan.offsets[j], images[j].size))
                resources_[ids[i]].sharesWith.push_back(ids[j]);
}

const FrameGraph::Resource* FrameGraph::overwriter(const Resource& r) const {
    for (uint32_t q : r.sharesWith)
        if (resources_[q].firstPass > r.firstPass) return &resources_[q];
    return nullptr;
}

bool FrameGraph::readable(ImageRef ref) const {
    return overwriter(resources_[resolve(ref)]) == nullptr;
}

void FrameGraph::checkReadable(const Resource& r) const {
    if (const Resource* q = overwriter(r))
        throw std::logic_error(
            r.image.name + " shares its memory with " + q->image.name +
            ", which a later pass of the frame writes: keep it (FrameGraph::keep, "
            "RenderOptions::keep) to read it after the frame");
}

FrameGraph::SharedMemory FrameGraph::sharedMemory() const {
    SharedMemory shared{sharedBytes_, {}};
    for (const Resource& r : resources_)
        if (r.shared) shared.images.push_back(r.image.name);
    return shared;
}

VkDeviceSize FrameGraph::heldMemory() const {
    VkDeviceSize bytes = sharedBytes_;
    for (const Resource& r : resources_)
        if (r.image.image && !r.shared) bytes += r.image.memorySize;
    return bytes;
}

std::vector<FrameGraph::HeldImage> FrameGraph::imageMemory() const {
    std::vector<HeldImage> list;
    for (const Resource& r : resources_)
        if (r.image.image) // not released
            list.push_back({r.image.name, r.image.memorySize, r.historyPair});
    return list;
}

} // namespace ssgi::graph
