// A small frame graph: passes run in the order they are added; each declares the images it
// reads and writes, and the graph records the vkCmdPipelineBarrier2 between them. History images
// are a graph feature: a pair that swaps each frame, contents kept, with "no history" on the
// first frame and after a reset. Every pass is wrapped in a debug label and a timestamp pair.
#pragma once

#include "graph/barriers.h"
#include "profiling.h"
#include "vk/resources.h"

#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace ssgi {
struct FrameState;
}

namespace ssgi::graph {

// Names an image as a pass sees it: a plain image, or one side of a history pair, resolved to a
// real image each frame.
struct ImageRef {
    enum class Kind { Plain, HistoryPrevious, HistoryCurrent };
    Kind kind = Kind::Plain;
    uint32_t index = UINT32_MAX;
    bool valid() const { return index != UINT32_MAX; }
};

struct ImageUse {
    ImageRef image;
    Use use;
};

using ssgi::PassTiming;

// How the graph makes its timestamps tell the truth on a device (see writeTimestamp() in
// frame_graph.cpp for why a CPU device needs more than the stamps themselves).
enum class TimestampMode {
    AsRecorded,       // a GPU writes a stamp when the work before it has passed the stage
    BarrierAfterEach, // lavapipe: a full barrier after each stamp makes it run when it should
};
TimestampMode timestampModeFor(VkPhysicalDeviceType deviceType);

// What record() put into the command buffer, in order, for inspection (tests). A pass turned off
// this frame records only its two timestamps back to back (they span nothing), listed as no
// command here.
struct RecordedCommand {
    enum class Kind { Barrier, Timestamp, TimestampBarrier, Pass };
    Kind kind;
    std::string pass;
};

// One barrier the graph emitted, for inspection (tests, --profile).
struct BarrierRecord {
    std::string pass, image;
    VkImageLayout oldLayout, newLayout;
    VkPipelineStageFlags2 srcStages, dstStages;
    VkAccessFlags2 srcAccess, dstAccess;
};

class FrameGraph;

// What a pass's record function gets: the command buffer, this frame's state, and the images
// behind the refs it declared. A ref the pass did not declare is refused (std::logic_error naming
// the pass): no barrier was derived for it.
struct PassContext {
    VkCommandBuffer cmd;
    const FrameState& frame;
    const FrameGraph& graph;
    const std::string& pass;
    const std::vector<ImageUse>& uses;
    const vk::Image& image(ImageRef ref) const;
};

using RecordFn = std::function<void(const PassContext&)>;
// Whether a pass runs this frame.
using EnabledFn = std::function<bool(const FrameState&)>;

class FrameGraph {
public:
    // Timestamps as the device needs them (timestampModeFor its type), or as `mode` says.
    explicit FrameGraph(vk::Context& ctx);
    FrameGraph(vk::Context& ctx, TimestampMode mode);
    ~FrameGraph();
    FrameGraph(const FrameGraph&) = delete;
    FrameGraph& operator=(const FrameGraph&) = delete;

    // An image whose contents live within one frame: the graph discards them at its first use,
    // and it shares memory with the other transient images whose lifetimes (from the first pass
    // that uses one to the last) do not overlap its own (transient_memory.h; placed when the
    // first frame is recorded). A persistent image keeps its contents from frame to frame (a
    // pass may skip rewriting it) and its memory to itself.
    ImageRef createImage(const std::string& name, VkFormat format, VkExtent2D extent,
                         VkImageUsageFlags usage, bool persistent = false);
    // A transient image that must still hold this frame's contents after the frame (to be
    // downloaded): its lifetime runs to the frame's end. keepAll() does so for every image.
    // Before the first frame only; an image a later pass of the frame overwrote cannot be read
    // (download() says so, naming both).
    void keep(ImageRef ref);
    void keepAll();
    // Whether download() can read the image after the frame: no later pass of the frame wrote
    // the memory it shares (kept, persistent, or written last). After the first frame.
    bool readable(ImageRef ref) const;
    // Places and binds the transient images (planTransientMemory), once every pass is added;
    // the first record() does it if nobody did.
    void allocateTransients();
    // A history pair: previous() is last frame's current(); contents are never discarded.
    uint32_t createHistory(const std::string& name, VkFormat format, VkExtent2D extent,
                           VkImageUsageFlags usage);
    static ImageRef previous(uint32_t history) {
        return {ImageRef::Kind::HistoryPrevious, history};
    }
    static ImageRef current(uint32_t history) { return {ImageRef::Kind::HistoryCurrent, history}; }
    // False on the first frame and after resetHistory(): previous() holds nothing to read.
    bool hasHistory(uint32_t history) const { return histories_[history].valid; }
    void resetHistory();
    void resetHistory(uint32_t history) { histories_[history].valid = false; }

    // `enabled`, when given, is asked each frame; a pass it turns off records nothing, touches
    // none of its images, and reports 0 ms.
    void addPass(const std::string& name, PassKind kind, std::vector<ImageUse> uses,
                 RecordFn record, EnabledFn enabled = {});

    // Records every pass of one frame (barriers, labels, timestamps) into cmd; `frame` is what
    // the passes' enable and record callbacks are handed (a default one without).
    void record(VkCommandBuffer cmd, const FrameState& frame);
    void record(VkCommandBuffer cmd);
    // After the frame's submission has completed: reads the timestamps and swaps histories.
    void endFrame();
    // Each pass of the last frame, its times from the frame's first stamp.
    const std::vector<PassTiming>& timings() const { return timings_; }
    TimestampMode timestampMode() const { return timestampMode_; }
    // With the log on, record() keeps what it recorded for inspection (off unless asked for):
    // the barriers of the last record() call, in order, and everything it recorded, in order.
    void setRecordingLog(bool on) { logRecording_ = on; }
    const std::vector<BarrierRecord>& lastBarriers() const { return lastBarriers_; }
    const std::vector<RecordedCommand>& lastCommands() const { return lastCommands_; }

    const vk::Image& image(ImageRef ref) const;
    // Copies an image (or the part of it `area` names) to the host as RGBA float (depth: R =
    // depth), after the last frame.
    std::vector<float> download(ImageRef ref, std::optional<VkRect2D> area = std::nullopt);
    // Copies an image (or its `area`) to the host as its texels lie (its own format, rows
    // tightly packed).
    std::vector<uint8_t> readTexels(ImageRef ref, std::optional<VkRect2D> area = std::nullopt);
    // For the next frame only, previous(history) is an image of `extent` holding `texels` (the
    // pair's format, rows tightly packed), and the pair counts as valid: a renderer of another
    // size hands its last frame over (Renderer::continueFrom). The frame's passes read it as any
    // last frame, at its own size; after the frame it is released and the pair is as before.
    void carryHistory(uint32_t history, VkExtent2D extent, const std::vector<uint8_t>& texels);
    // Records into cmd (submitted after the last frame) the barrier that makes the image a
    // transfer source, keeping the graph's record of its state (the viewer copies the frame out).
    const vk::Image& prepareTransferSource(VkCommandBuffer cmd, ImageRef ref);
    ImageRef find(const std::string& name) const;
    // Takes `from`'s persistent image `name` (not a history's side), its contents and state, in
    // place of this graph's own of that name, which `from` gets back to destroy with itself:
    // a renderer made from another's parts keeps what that one drew (Renderer's taking
    // constructor). False, and nothing changes, where either graph lacks it, it is transient in
    // either, or its format, extent or usage differ.
    bool adopt(const std::string& name, FrameGraph& from);
    // Every image the graph owns (history pairs as two), with the device memory it needs.
    struct HeldImage {
        std::string name;
        VkDeviceSize bytes = 0;
        std::string historyPair; // for one side of a history pair, the pair's name; else empty
    };
    std::vector<HeldImage> imageMemory() const;
    // The transient images that share one block of memory, and the block's size (0 before the
    // first frame); the memory the graph holds is that block plus every other image's own.
    struct SharedMemory {
        VkDeviceSize bytes = 0;
        std::vector<std::string> images;
    };
    SharedMemory sharedMemory() const;
    VkDeviceSize heldMemory() const;

private:
    struct Resource {
        vk::Image image;
        ImageState state;
        bool transient = true;
        bool kept = false;                // keep(): lives to the frame's end
        bool shared = false;              // bound into sharedBlock_
        std::vector<uint32_t> sharesWith; // the resources whose bytes overlap its own
        uint32_t firstPass = 0;           // its lifetime within the frame (shared ones)
        std::string historyPair;          // the pair it is a side of, if any
    };
    struct History {
        uint32_t resources[2];
        uint32_t currentSlot = 0;
        bool valid = false;
        VkImageUsageFlags usage = 0;
        std::optional<uint32_t> carried; // carryHistory()'s image, read in place of previous()
    };
    struct Pass {
        std::string name;
        PassKind kind;
        std::vector<ImageUse> uses;
        RecordFn record;
        EnabledFn enabled;
    };
    uint32_t resolve(ImageRef ref) const;
    // Records the barrier (if any) that readies `r` for a transfer `use`, outside any pass.
    void transferBarrier(VkCommandBuffer cmd, Resource& r, Use use, bool discard);
    void writeTimestamp(VkCommandBuffer cmd, uint32_t query, const std::string& pass);
    uint32_t addResource(const std::string& name, VkFormat format, VkExtent2D extent,
                         VkImageUsageFlags usage, bool transient);
    // The image a later pass of the frame writes over `r`'s memory with, or none.
    const Resource* overwriter(const Resource& r) const;
    // Throws std::logic_error where a later pass of the frame writes over `r`'s memory.
    void checkReadable(const Resource& r) const;

    vk::Context& ctx_;
    std::vector<Resource> resources_;
    std::vector<History> histories_;
    std::vector<Pass> passes_;
    std::vector<PassTiming> timings_;
    bool logRecording_ = false;
    std::vector<BarrierRecord> lastBarriers_;
    std::vector<RecordedCommand> lastCommands_;
    TimestampMode timestampMode_;
    std::vector<bool> ran_; // per pass, in the last recorded frame
    VkQueryPool queryPool_ = VK_NULL_HANDLE;
    uint32_t queryCapacity_ = 0;
    // One compute-invocation count a pass (PassTiming::invocations), where the device has
    // pipeline statistics queries.
    VkQueryPool statisticsPool_ = VK_NULL_HANDLE;
    bool allocated_ = false; // allocateTransients() has run
    bool keepAll_ = false;
    VkDeviceMemory sharedBlock_ = VK_NULL_HANDLE;
    VkDeviceSize sharedBytes_ = 0;
};

} // namespace ssgi::graph
