// The ceiling probe: what the device reaches at all in trivial kernels (texel fetches with the
// locality of a screen-space kernel and of a VPL gather, and plain memory bandwidth). It is
// sampled once in every round of the timed frames, between the configurations' frames, so each
// pass can be reported as a fraction of it under the same load.
#include "bench.h"

#include "app/cli.h"
#include "frame_state.h"
#include "graph/frame_graph.h"
#include "vk/pipeline.h"

#include <chrono>

namespace ssgi::bench {

namespace {

constexpr int kTaps = 64;
constexpr int kLocalSpread = 32;          // taps within +-32 texels: an AO or PCF kernel's reach
constexpr uint32_t kScatteredSize = 1024; // the default RSM's size
constexpr uint32_t kBandwidthSize = 2048; // 64 MiB per RGBA32F image: beyond any CPU cache
constexpr uint32_t kBandwidthBytesPerPixel = 32;

struct ProbePush {
    int32_t size[4];
};

} // namespace

// One kernel reading `source` (filled once, a persistent image) and writing `target`. Its time
// is the host's wall clock around a frame that runs the kernel alone, less that of an empty
// frame; the graph's timestamp is kept beside it (on lavapipe the rasterizer threads write a
// timestamp when they reach the query, which can be after compute work recorded after it).
struct CeilingProbe::Kernel {
    graph::FrameGraph graph;
    enum { Fill, Run, Empty } phase = Fill;
    std::vector<double> host, empty, stamps;

    Kernel(vk::Context& ctx, VkExtent2D sourceSize, VkExtent2D targetSize, VkFormat targetFormat,
           const vk::Pipeline& fill, const vk::Pipeline& kernel, VkSampler sampler, ProbePush push)
        : graph(ctx) {
        const VkImageUsageFlags usage = VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT;
        const graph::ImageRef source = graph.createImage(
            "probe.source", VK_FORMAT_R32G32B32A32_SFLOAT, sourceSize, usage, true);
        const graph::ImageRef target =
            graph.createImage("probe.target", targetFormat, targetSize, usage);
        using graph::Use;
        graph.addPass(
            "fill", graph::PassKind::Compute, {{source, Use::StorageWrite}},
            [&ctx, &fill, source, sourceSize](const graph::PassContext& pc) {
                vk::Descriptors().storageImage(0, pc.image(source).view).push(ctx, pc.cmd, fill);
                const ProbePush size{{int(sourceSize.width), int(sourceSize.height), 0, 0}};
                vk::dispatch(pc.cmd, fill, sourceSize.width, sourceSize.height, size);
            },
            [this](const FrameState&) { return phase == Fill; });
        graph.addPass(
            "kernel", graph::PassKind::Compute,
            {{source, Use::Sampled}, {target, Use::StorageWrite}},
            [&ctx, &kernel, sampler, source, target, targetSize,
             push](const graph::PassContext& pc) {
                vk::Descriptors()
                    .sampledImage(0, pc.image(source).view, sampler)
                    .storageImage(1, pc.image(target).view)
                    .push(ctx, pc.cmd, kernel);
                vk::dispatch(pc.cmd, kernel, targetSize.width, targetSize.height, push);
            },
            [this](const FrameState&) { return phase == Run; });
        frame(ctx, Fill);
    }

    double frame(vk::Context& ctx, decltype(phase) p) {
        phase = p;
        const vk::HostSpan span =
            ctx.submitAndWait([&](VkCommandBuffer cmd) { graph.record(cmd); });
        graph.endFrame();
        return span.milliseconds;
    }

    void sample(vk::Context& ctx) {
        host.push_back(frame(ctx, Run));
        stamps.push_back(graph.timings()[1].milliseconds);
        empty.push_back(frame(ctx, Empty));
    }

    // Medians over the samples after the first `skip`.
    double hostMs(size_t skip) const {
        return cli::median({host.begin() + skip, host.end()}) -
               cli::median({empty.begin() + skip, empty.end()});
    }
    double timestampMs(size_t skip) const {
        return cli::median({stamps.begin() + skip, stamps.end()});
    }
};

CeilingProbe::CeilingProbe(vk::Context& ctx, VkExtent2D target) : ctx_(ctx), target_(target) {
    const VkDescriptorType sampled = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
    const VkDescriptorType storage = VK_DESCRIPTOR_TYPE_STORAGE_IMAGE;
    pipelines_ = {vk::createComputePipeline(ctx, "probe_fill.comp", {storage}, sizeof(ProbePush)),
                  vk::createComputePipeline(ctx, "probe_taps.comp", {sampled, storage},
                                            sizeof(ProbePush),
                                            {{{"TAPS", kTaps}, {"SPREAD", kLocalSpread}}}),
                  vk::createComputePipeline(ctx, "probe_taps.comp", {sampled, storage},
                                            sizeof(ProbePush), {{{"TAPS", kTaps}, {"SPREAD", 0}}}),
                  vk::createComputePipeline(ctx, "probe_bandwidth.comp", {sampled, storage},
                                            sizeof(ProbePush))};
    sampler_ = vk::createSampler(ctx, VK_FILTER_NEAREST, VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE);
    // The local source has the target's size rounded up to a power of two (the kernel masks).
    uint32_t local = 1;
    while (local < std::max(target.width, target.height))
        local *= 2;
    const VkFormat half = VK_FORMAT_R16G16B16A16_SFLOAT;
    const int w = int(target.width), h = int(target.height), s = int(kScatteredSize),
              b = int(kBandwidthSize);
    kernels_.push_back(std::make_unique<Kernel>(ctx, VkExtent2D{local, local}, target, half,
                                                pipelines_[0], pipelines_[1], sampler_,
                                                ProbePush{{w, h, int(local), int(local)}}));
    kernels_.push_back(std::make_unique<Kernel>(ctx, VkExtent2D{kScatteredSize, kScatteredSize},
                                                target, half, pipelines_[0], pipelines_[2],
                                                sampler_, ProbePush{{w, h, s, s}}));
    kernels_.push_back(std::make_unique<Kernel>(ctx, VkExtent2D{kBandwidthSize, kBandwidthSize},
                                                VkExtent2D{kBandwidthSize, kBandwidthSize},
                                                VK_FORMAT_R32G32B32A32_SFLOAT, pipelines_[0],
                                                pipelines_[3], sampler_, ProbePush{{b, b, 0, 0}}));
}

CeilingProbe::~CeilingProbe() {
    kernels_.clear();
    for (vk::Pipeline& p : pipelines_)
        vk::destroyPipeline(ctx_, p);
    vkDestroySampler(ctx_.device, sampler_, nullptr);
}

void CeilingProbe::sample() {
    for (auto& kernel : kernels_)
        kernel->sample(ctx_);
}

Json CeilingProbe::json(size_t skip) const {
    const double taps = double(target_.width) * target_.height * kTaps;
    const double bytes = double(kBandwidthSize) * kBandwidthSize * kBandwidthBytesPerPixel;
    const Kernel &local = *kernels_[0], &scattered = *kernels_[1], &bandwidth = *kernels_[2];
    return {{"taps_per_pixel", kTaps},
            {"local_spread_texels", kLocalSpread},
            {"scattered_source_texels", kScatteredSize},
            {"bandwidth_image_texels", kBandwidthSize},
            {"samples", local.host.size() - skip},
            {"host_ms",
             {{"taps_local", local.hostMs(skip)},
              {"taps_scattered", scattered.hostMs(skip)},
              {"bandwidth", bandwidth.hostMs(skip)}}},
            {"timestamp_ms",
             {{"taps_local", local.timestampMs(skip)},
              {"taps_scattered", scattered.timestampMs(skip)},
              {"bandwidth", bandwidth.timestampMs(skip)}}},
            {"taps_local_per_ms", taps / local.hostMs(skip)},
            {"taps_scattered_per_ms", taps / scattered.hostMs(skip)},
            {"bytes_per_ms", bytes / bandwidth.hostMs(skip)}};
}

} // namespace ssgi::bench
