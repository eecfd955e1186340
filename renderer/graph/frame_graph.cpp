#include "graph/frame_graph.h"

#include "frame_state.h"
#include "vk/texel_decode.h"

#include <algorithm>
#include <cstring>
#include <stdexcept>

namespace ssgi::graph {

const vk::Image& PassContext::image(ImageRef ref) const {
    for (const ImageUse& use : uses)
        if (use.image.kind == ref.kind && use.image.index == ref.index) return graph.image(ref);
    throw std::logic_error("pass " + pass + " reaches for an image it did not declare (" +
                           (ref.valid() ? graph.image(ref).name : std::string("none")) + ")");
}

TimestampMode timestampModeFor(VkPhysicalDeviceType deviceType) {
    return deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU ? TimestampMode::BarrierAfterEach
                                                     : TimestampMode::AsRecorded;
}

FrameGraph::FrameGraph(vk::Context& ctx)
    : FrameGraph(ctx, timestampModeFor(ctx.properties.deviceType)) {}

FrameGraph::FrameGraph(vk::Context& ctx, TimestampMode mode) : ctx_(ctx), timestampMode_(mode) {}

FrameGraph::~FrameGraph() {
    vkDeviceWaitIdle(ctx_.device);
    for (Resource& r : resources_)
        vk::destroyImage(ctx_, r.image);
    if (sharedBlock_) vkFreeMemory(ctx_.device, sharedBlock_, nullptr);
    if (queryPool_) vkDestroyQueryPool(ctx_.device, queryPool_, nullptr);
    if (statisticsPool_) vkDestroyQueryPool(ctx_.device, statisticsPool_, nullptr);
}

uint32_t FrameGraph::addResource(const std::string& name, VkFormat format, VkExtent2D extent,
                                 VkImageUsageFlags usage, bool transient) {
    Resource r;
    usage |= VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
    // A transient image gets its memory when the first frame is recorded (allocateTransients).
    r.image = transient && !allocated_ ? vk::createUnboundImage(ctx_, name, format, extent, usage)
                                       : vk::createImage(ctx_, name, format, extent, usage);
    r.transient = transient;
    resources_.push_back(r);
    return uint32_t(resources_.size() - 1);
}

ImageRef FrameGraph::createImage(const std::string& name, VkFormat format, VkExtent2D extent,
                                 VkImageUsageFlags usage, bool persistent) {
    return {ImageRef::Kind::Plain, addResource(name, format, extent, usage, !persistent)};
}

uint32_t FrameGraph::createHistory(const std::string& name, VkFormat format, VkExtent2D extent,
                                   VkImageUsageFlags usage) {
    History h;
    // Histories may be copied into (a settled frame carries the last one over whole).
    usage |= VK_IMAGE_USAGE_TRANSFER_DST_BIT;
    h.usage = usage;
    h.resources[0] = addResource(name + " A", format, extent, usage, false);
    h.resources[1] = addResource(name + " B", format, extent, usage, false);
    resources_[h.resources[0]].historyPair = resources_[h.resources[1]].historyPair = name;
    histories_.push_back(h);
    return uint32_t(histories_.size() - 1);
}

void FrameGraph::resetHistory() {
    for (History& h : histories_)
        h.valid = false;
}

uint32_t FrameGraph::resolve(ImageRef ref) const {
    switch (ref.kind) {
    case ImageRef::Kind::Plain:
        return ref.index;
    case ImageRef::Kind::HistoryCurrent:
        return histories_[ref.index].resources[histories_[ref.index].currentSlot];
    case ImageRef::Kind::HistoryPrevious: {
        const History& h = histories_[ref.index];
        return h.carried ? *h.carried : h.resources[1 - h.currentSlot];
    }
    }
    return ref.index;
}

const vk::Image& FrameGraph::image(ImageRef ref) const {
    return resources_[resolve(ref)].image;
}

ImageRef FrameGraph::find(const std::string& name) const {
    for (uint32_t i = 0; i < resources_.size(); ++i)
        if (resources_[i].image.name == name) return {ImageRef::Kind::Plain, i};
    return {};
}

bool FrameGraph::adopt(const std::string& name, FrameGraph& from) {
    const ImageRef mine = find(name), theirs = from.find(name);
    if (!mine.valid() || !theirs.valid()) return false;
    Resource& a = resources_[mine.index];
    Resource& b = from.resources_[theirs.index];
    if (a.transient || b.transient || !a.historyPair.empty() || !b.historyPair.empty() ||
        a.image.format != b.image.format || a.image.extent.width != b.image.extent.width ||
        a.image.extent.height != b.image.extent.height || a.image.usage != b.image.usage)
        return false;
    std::swap(a.image, b.image);
    std::swap(a.state, b.state);
    return true;
}

void FrameGraph::addPass(const std::string& name, PassKind kind, std::vector<ImageUse> uses,
                         RecordFn record, EnabledFn enabled) {
    passes_.push_back({name, kind, std::move(uses), std::move(record), std::move(enabled)});
}

// A GPU writes a timestamp once the commands before it have passed the stage, which is what a
// pass's begin and end stamps mean. Lavapipe (Mesa 22.3, lvp_execute.c) does not: writing a
// timestamp flushes what came before, then bins the end-query into a new rasterizer scene that
// runs only at the next flush, while compute dispatches run at once and wait for themselves
// (llvmpipe_launch_grid). Without help a compute pass's begin stamp is written after its own
// dispatch has finished, and the pass reads about 0 ms while its time falls into the gap before
// it. A full barrier right after each stamp flushes it at once, so every stamp is taken where it
// stands; a barrier before a stamp does not help, since the stamp's own scene is what waits. It
// changes no image; a GPU records the stamps alone (docs/profiling.md has the figures).
void FrameGraph::writeTimestamp(VkCommandBuffer cmd, uint32_t query, const std::string& pass) {
    vkCmdWriteTimestamp2(cmd, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, queryPool_, query);
    if (logRecording_) lastCommands_.push_back({RecordedCommand::Kind::Timestamp, pass});
    if (timestampMode_ != TimestampMode::BarrierAfterEach) return;
    VkMemoryBarrier2 all{VK_STRUCTURE_TYPE_MEMORY_BARRIER_2};
    all.srcStageMask = all.dstStageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
    all.srcAccessMask = VK_ACCESS_2_MEMORY_WRITE_BIT;
    all.dstAccessMask = VK_ACCESS_2_MEMORY_READ_BIT | VK_ACCESS_2_MEMORY_WRITE_BIT;
    VkDependencyInfo dep{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
    dep.memoryBarrierCount = 1;
    dep.pMemoryBarriers = &all;
    vkCmdPipelineBarrier2(cmd, &dep);
    if (logRecording_) lastCommands_.push_back({RecordedCommand::Kind::TimestampBarrier, pass});
}

void FrameGraph::record(VkCommandBuffer cmd) {
    record(cmd, FrameState{});
}

void FrameGraph::record(VkCommandBuffer cmd, const FrameState& frame) {
    allocateTransients();
    const uint32_t queriesNeeded = uint32_t(2 * passes_.size());
    if (queryCapacity_ < queriesNeeded) {
        if (queryPool_) vkDestroyQueryPool(ctx_.device, queryPool_, nullptr);
        VkQueryPoolCreateInfo info{VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO};
        info.queryType = VK_QUERY_TYPE_TIMESTAMP;
        info.queryCount = queriesNeeded;
        VK_CHECK(vkCreateQueryPool(ctx_.device, &info, nullptr, &queryPool_));
        if (ctx_.pipelineStatistics) {
            if (statisticsPool_) vkDestroyQueryPool(ctx_.device, statisticsPool_, nullptr);
            info.queryType = VK_QUERY_TYPE_PIPELINE_STATISTICS;
            info.pipelineStatistics = VK_QUERY_PIPELINE_STATISTIC_COMPUTE_SHADER_INVOCATIONS_BIT;
            info.queryCount = queriesNeeded / 2;
            VK_CHECK(vkCreateQueryPool(ctx_.device, &info, nullptr, &statisticsPool_));
        }
        queryCapacity_ = queriesNeeded;
    }
    vkCmdResetQueryPool(cmd, queryPool_, 0, queryCapacity_);
    if (statisticsPool_) vkCmdResetQueryPool(cmd, statisticsPool_, 0, queryCapacity_ / 2);

    std::vector<bool> touched(resources_.size(), false);
    lastBarriers_.clear();
    lastCommands_.clear();
    ran_.assign(passes_.size(), false);
    for (uint32_t p = 0; p < passes_.size(); ++p) {
        const Pass& pass = passes_[p];
        if (pass.enabled && !pass.enabled(frame)) {
            // Both stamps together: the pass spans nothing, where it would have stood.
            vkCmdWriteTimestamp2(cmd, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, queryPool_, 2 * p);
            vkCmdWriteTimestamp2(cmd, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, queryPool_, 2 * p + 1);
            if (statisticsPool_) { // and no invocations
                vkCmdBeginQuery(cmd, statisticsPool_, p, 0);
                vkCmdEndQuery(cmd, statisticsPool_, p);
            }
            continue;
        }
        ran_[p] = true;
        std::vector<VkImageMemoryBarrier2> barriers;
        for (const ImageUse& use : pass.uses) {
            const uint32_t id = resolve(use.image);
            Resource& r = resources_[id];
            const bool discard = r.transient && !touched[id];
            touched[id] = true;
            // Memory another image used before: its first use here waits for every use of
            // theirs (the write and the reads since), as it would for its own.
            if (discard)
                for (uint32_t q : r.sharesWith) {
                    const ImageState& other = resources_[q].state;
                    r.state.writeStages |= other.writeStages | other.readStages;
                    r.state.writeAccess |= other.writeAccess;
                }
            if (auto b = transition(r.state, use.use, pass.kind, discard, r.image.image,
                                    r.image.aspect)) {
                barriers.push_back(*b);
                if (logRecording_)
                    lastBarriers_.push_back({pass.name, r.image.name, b->oldLayout, b->newLayout,
                                             b->srcStageMask, b->dstStageMask, b->srcAccessMask,
                                             b->dstAccessMask});
            }
        }
        if (!barriers.empty()) {
            VkDependencyInfo dep{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
            dep.imageMemoryBarrierCount = uint32_t(barriers.size());
            dep.pImageMemoryBarriers = barriers.data();
            vkCmdPipelineBarrier2(cmd, &dep);
            if (logRecording_) lastCommands_.push_back({RecordedCommand::Kind::Barrier, pass.name});
        }
        if (ctx_.cmdBeginLabel) {
            VkDebugUtilsLabelEXT label{VK_STRUCTURE_TYPE_DEBUG_UTILS_LABEL_EXT};
            label.pLabelName = pass.name.c_str();
            ctx_.cmdBeginLabel(cmd, &label);
        }
        writeTimestamp(cmd, 2 * p, pass.name);
        if (statisticsPool_) vkCmdBeginQuery(cmd, statisticsPool_, p, 0);
        pass.record(PassContext{cmd, frame, *this, pass.name, pass.uses});
        if (statisticsPool_) vkCmdEndQuery(cmd, statisticsPool_, p);
        if (logRecording_) lastCommands_.push_back({RecordedCommand::Kind::Pass, pass.name});
        writeTimestamp(cmd, 2 * p + 1, pass.name);
        if (ctx_.cmdEndLabel) ctx_.cmdEndLabel(cmd);
    }
}

void FrameGraph::endFrame() {
    std::vector<uint64_t> stamps(2 * passes_.size());
    if (!stamps.empty())
        VK_CHECK(vkGetQueryPoolResults(
            ctx_.device, queryPool_, 0, uint32_t(stamps.size()), stamps.size() * sizeof(uint64_t),
            stamps.data(), sizeof(uint64_t), VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT));
    std::vector<uint64_t> invocations(passes_.size(), 0);
    if (statisticsPool_ && !invocations.empty())
        VK_CHECK(vkGetQueryPoolResults(
            ctx_.device, statisticsPool_, 0, uint32_t(invocations.size()),
            invocations.size() * sizeof(uint64_t), invocations.data(), sizeof(uint64_t),
            VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT));
    const double period = ctx_.properties.limits.timestampPeriod; // ns per tick
    timings_.clear();
    const uint64_t first = stamps.empty() ? 0 : stamps[0];
    auto ms = [&](uint64_t stamp) { return double(int64_t(stamp - first)) * period * 1e-6; };
    for (uint32_t p = 0; p < passes_.size(); ++p) {
        const bool ran = p < ran_.size() && ran_[p];
        const double start = ms(stamps[2 * p]), end = ms(stamps[2 * p + 1]);
        timings_.push_back(
            {passes_[p].name, ran ? end - start : 0.0, start, end, ran, invocations[p]});
    }
    for (History& h : histories_) {
        h.currentSlot = 1 - h.currentSlot;
        h.valid = true;
        if (h.carried) { // read by this frame, needed no more (the frame has completed)
            vk::destroyImage(ctx_, resources_[*h.carried].image);
            h.carried.reset();
        }
    }
}

void FrameGraph::transferBarrier(VkCommandBuffer cmd, Resource& r, Use use, bool discard) {
    if (auto b =
            transition(r.state, use, PassKind::Transfer, discard, r.image.image, r.image.aspect)) {
        VkDependencyInfo dep{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
        dep.imageMemoryBarrierCount = 1;
        dep.pImageMemoryBarriers = &*b;
        vkCmdPipelineBarrier2(cmd, &dep);
    }
}

const vk::Image& FrameGraph::prepareTransferSource(VkCommandBuffer cmd, ImageRef ref) {
    allocateTransients(); // an image read before any frame holds nothing, but has memory
    Resource& r = resources_[resolve(ref)];
    checkReadable(r);
    transferBarrier(cmd, r, Use::TransferSrc, false);
    return r.image;
}

std::vector<uint8_t> FrameGraph::readTexels(ImageRef ref, std::optional<VkRect2D> area) {
    allocateTransients();
    Resource& r = resources_[resolve(ref)];
    checkReadable(r);
    const VkRect2D a = area.value_or(VkRect2D{{0, 0}, r.image.extent});
    const VkDeviceSize size =
        VkDeviceSize(a.extent.width) * a.extent.height * vk::formatTexelSize(r.image.format);
    vk::Buffer staging = vk::createBuffer(ctx_, size, VK_BUFFER_USAGE_TRANSFER_DST_BIT, true);
    ctx_.submitAndWait([&](VkCommandBuffer cmd) {
        prepareTransferSource(cmd, ref);
        VkBufferImageCopy region{};
        region.imageSubresource = {r.image.aspect, 0, 0, 1};
        region.imageOffset = {a.offset.x, a.offset.y, 0};
        region.imageExtent = {a.extent.width, a.extent.height, 1};
        vkCmdCopyImageToBuffer(cmd, r.image.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                               staging.buffer, 1, &region);
    });
    const auto* bytes = static_cast<const uint8_t*>(staging.mapped);
    std::vector<uint8_t> texels(bytes, bytes + size);
    vk::destroyBuffer(ctx_, staging);
    return texels;
}

void FrameGraph::carryHistory(uint32_t history, VkExtent2D extent,
                              const std::vector<uint8_t>& texels) {
    History& h = histories_[history];
    const vk::Image& pair = resources_[h.resources[0]].image;
    const VkDeviceSize size =
        VkDeviceSize(extent.width) * extent.height * vk::formatTexelSize(pair.format);
    if (texels.size() != size)
        throw std::logic_error("carryHistory: " + pair.name + " at " +
                               std::to_string(extent.width) + "x" + std::to_string(extent.height) +
                               " takes " + std::to_string(size) + " bytes, not " +
                               std::to_string(texels.size()));
    const std::string name = pair.name.substr(0, pair.name.size() - 2) + " carried";
    const uint32_t id = addResource(name, pair.format, extent, h.usage, false);
    Resource& r = resources_[id];
    vk::Buffer staging = vk::createBuffer(ctx_, size, VK_BUFFER_USAGE_TRANSFER_SRC_BIT, true);
    std::memcpy(staging.mapped, texels.data(), size);
    ctx_.submitAndWait([&](VkCommandBuffer cmd) {
        transferBarrier(cmd, r, Use::TransferDst, true); // what it held is not needed
        VkBufferImageCopy region{};
        region.imageSubresource = {r.image.aspect, 0, 0, 1};
        region.imageExtent = {extent.width, extent.height, 1};
        vkCmdCopyBufferToImage(cmd, staging.buffer, r.image.image,
                               VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &region);
    });
    vk::destroyBuffer(ctx_, staging);
    h.carried = id;
    h.valid = true;
}

std::vector<float> FrameGraph::download(ImageRef ref, std::optional<VkRect2D> area) {
    const vk::Image& image = resources_[resolve(ref)].image;
    const VkExtent2D e = area ? area->extent : image.extent;
    const std::vector<uint8_t> texels = readTexels(ref, area);
    return vk::decodeTexels(image.format, texels.data(), size_t(e.width) * e.height, image.name);
}

} // namespace ssgi::graph
