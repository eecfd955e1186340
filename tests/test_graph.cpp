// The frame graph: declared image uses -> emitted barriers (CPU), where transient images lie in
// memory (CPU), and history pairs and shared memory on the device.
#include "frame_state.h"
#include "graph/frame_graph.h"
#include "graph/transient_memory.h"
#include "support.h"

using namespace ssgi;
using namespace ssgi::graph;

namespace {

const VkImage kImage = reinterpret_cast<VkImage>(uintptr_t(0x1234));
const VkImageAspectFlags kColor = VK_IMAGE_ASPECT_COLOR_BIT;

TEST(Barriers, FirstWriteDiscardsAndWaitsForNothing) {
    ImageState s;
    auto b = transition(s, Use::ColorAttachment, PassKind::Graphics, true, kImage, kColor);
    ASSERT_TRUE(b);
    EXPECT_EQ(b->oldLayout, VK_IMAGE_LAYOUT_UNDEFINED);
    EXPECT_EQ(b->newLayout, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL);
    EXPECT_EQ(b->srcStageMask, VK_PIPELINE_STAGE_2_NONE);
    EXPECT_EQ(b->srcAccessMask, VK_ACCESS_2_NONE);
    EXPECT_EQ(b->dstStageMask, VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT);
    EXPECT_EQ(b->image, kImage);
}

TEST(Barriers, ReadAfterAttachmentWriteMakesTheWriteVisibleAndChangesLayout) {
    ImageState s;
    transition(s, Use::ColorAttachment, PassKind::Graphics, true, kImage, kColor);
    auto b = transition(s, Use::Sampled, PassKind::Compute, false, kImage, kColor);
    ASSERT_TRUE(b);
    EXPECT_EQ(b->oldLayout, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL);
    EXPECT_EQ(b->newLayout, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
    EXPECT_EQ(b->srcStageMask, VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT);
    EXPECT_EQ(b->srcAccessMask, VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT);
    EXPECT_EQ(b->dstStageMask, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT);
    EXPECT_EQ(b->dstAccessMask, VK_ACCESS_2_SHADER_SAMPLED_READ_BIT);
}

TEST(Barriers, ReadAfterReadInTheSameStageNeedsNoBarrier) {
    ImageState s;
    transition(s, Use::StorageWrite, PassKind::Compute, true, kImage, kColor);
    ASSERT_TRUE(transition(s, Use::Sampled, PassKind::Compute, false, kImage, kColor));
    EXPECT_FALSE(transition(s, Use::Sampled, PassKind::Compute, false, kImage, kColor));
}

TEST(Barriers, ReadInAnotherStageChainsOnTheFirstReader) {
    ImageState s;
    transition(s, Use::ColorAttachment, PassKind::Graphics, true, kImage, kColor);
    transition(s, Use::Sampled, PassKind::Compute, false, kImage, kColor);
    auto b = transition(s, Use::Sampled, PassKind::Graphics, false, kImage, kColor);
    ASSERT_TRUE(b);
    EXPECT_EQ(b->oldLayout, b->newLayout);
    EXPECT_EQ(b->srcStageMask, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT);
    EXPECT_EQ(b->dstStageMask, VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT);
}

TEST(Barriers, StorageWriteThenReadKeepsGeneralLayout) {
    ImageState s;
    transition(s, Use::StorageWrite, PassKind::Compute, true, kImage, kColor);
    auto b = transition(s, Use::StorageRead, PassKind::Compute, false, kImage, kColor);
    ASSERT_TRUE(b);
    EXPECT_EQ(b->oldLayout, VK_IMAGE_LAYOUT_GENERAL);
    EXPECT_EQ(b->newLayout, VK_IMAGE_LAYOUT_GENERAL);
    EXPECT_EQ(b->srcAccessMask, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
    EXPECT_EQ(b->dstAccessMask, VK_ACCESS_2_SHADER_STORAGE_READ_BIT);
}

TEST(Barriers, WriteAfterWriteWaitsForTheEarlierWrite) {
    ImageState s;
    transition(s, Use::StorageWrite, PassKind::Compute, true, kImage, kColor);
    auto b = transition(s, Use::StorageWrite, PassKind::Compute, false, kImage, kColor);
    ASSERT_TRUE(b);
    EXPECT_EQ(b->srcStageMask, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT);
    EXPECT_EQ(b->srcAccessMask, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
}

TEST(Barriers, WriteAfterReadWaitsForEveryReaderButFlushesNothing) {
    ImageState s;
    transition(s, Use::ColorAttachment, PassKind::Graphics, true, kImage, kColor);
    transition(s, Use::Sampled, PassKind::Compute, false, kImage, kColor);
    transition(s, Use::Sampled, PassKind::Graphics, false, kImage, kColor);
    // Next frame: the transient image is discarded and drawn into again.
    auto b = transition(s, Use::ColorAttachment, PassKind::Graphics, true, kImage, kColor);
    ASSERT_TRUE(b);
    EXPECT_EQ(b->oldLayout, VK_IMAGE_LAYOUT_UNDEFINED);
    EXPECT_EQ(b->srcStageMask,
              VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT);
    EXPECT_EQ(b->srcAccessMask, VK_ACCESS_2_NONE);
}

TEST(Barriers, HistoryIsNeverDiscarded) {
    ImageState s;
    transition(s, Use::StorageWrite, PassKind::Compute, true, kImage, kColor);
    transition(s, Use::Sampled, PassKind::Compute, false, kImage, kColor);
    auto b = transition(s, Use::StorageReadWrite, PassKind::Compute, false, kImage, kColor);
    ASSERT_TRUE(b);
    EXPECT_EQ(b->oldLayout, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
    EXPECT_EQ(b->newLayout, VK_IMAGE_LAYOUT_GENERAL);
}

TEST(Barriers, DepthAttachmentUsesBothFragmentTestStages) {
    UseInfo info = useInfo(Use::DepthAttachment, PassKind::Graphics);
    EXPECT_EQ(info.layout, VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL);
    EXPECT_EQ(info.stages, VK_PIPELINE_STAGE_2_EARLY_FRAGMENT_TESTS_BIT |
                               VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT);
    EXPECT_TRUE(info.writes);
}

// Transient images whose lifetimes do not overlap share bytes; those that overlap do not.
TEST(TransientMemory, ImagesThatNeverLiveAtOnceShareTheirBytes) {
    // a: passes 0-1, b: 2-3 (after a), c: 1-2 (beside both).
    const std::vector<TransientImage> images = {
        {100, 1, ~0u, 0, 1}, {100, 1, ~0u, 2, 3}, {50, 1, ~0u, 1, 2}};
    const TransientPlan plan = planTransientMemory(images);
    ASSERT_TRUE(plan.offsets[0] && plan.offsets[1] && plan.offsets[2]);
    EXPECT_EQ(*plan.offsets[0], *plan.offsets[1]) << "a and b take turns";
    EXPECT_FALSE(shareMemory(*plan.offsets[2], 50, *plan.offsets[0], 100));
    EXPECT_EQ(plan.blockSize, 150u) << "the block holds the most that lives at once";
}

TEST(TransientMemory, OffsetsKeepEachImagesAlignment) {
    const std::vector<TransientImage> images = {{100, 64, ~0u, 0, 0}, {10, 256, ~0u, 0, 0}};
    const TransientPlan plan = planTransientMemory(images);
    ASSERT_TRUE(plan.offsets[0] && plan.offsets[1]);
    EXPECT_EQ(*plan.offsets[1] % 256, 0u);
    EXPECT_FALSE(shareMemory(*plan.offsets[0], 100, *plan.offsets[1], 10));
}

TEST(TransientMemory, AnImageOfAnotherMemoryTypeGetsItsOwn) {
    const std::vector<TransientImage> images = {{100, 1, 0b01, 0, 0}, {100, 1, 0b10, 1, 1}};
    const TransientPlan plan = planTransientMemory(images);
    EXPECT_EQ(plan.memoryTypeBits, 0b01u);
    EXPECT_TRUE(plan.offsets[0]);
    EXPECT_FALSE(plan.offsets[1]);
    EXPECT_EQ(plan.blockSize, 100u);
}

// History on the device: each frame clears the current image to the frame number and copies
// the previous one into a plain image; contents must survive the swap, under sync validation.
class HistoryTest : public test::VulkanTest {};

TEST_F(HistoryTest, PairSwapsKeepsContentsAndReportsNoHistoryFirst) {
    vk::Context& ctx = test::context();
    FrameGraph graph(ctx);
    const VkImageUsageFlags usage =
        VK_IMAGE_USAGE_TRANSFER_DST_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
    const uint32_t history =
        graph.createHistory("value", VK_FORMAT_R32G32B32A32_SFLOAT, {4, 4}, usage);
    const ImageRef copy = graph.createImage("copy", VK_FORMAT_R32G32B32A32_SFLOAT, {4, 4}, usage);
    float frameValue = 0.0f;
    graph.addPass("write current", PassKind::Transfer,
                  {{FrameGraph::current(history), Use::TransferDst}}, [&](const PassContext& pc) {
                      VkClearColorValue value{{frameValue, 0, 0, 1}};
                      VkImageSubresourceRange range{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
                      vkCmdClearColorImage(pc.cmd, pc.image(FrameGraph::current(history)).image,
                                           VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, &value, 1, &range);
                  });
    graph.addPass("copy previous", PassKind::Transfer,
                  {{FrameGraph::previous(history), Use::TransferSrc}, {copy, Use::TransferDst}},
                  [&](const PassContext& pc) {
                      VkImageCopy region{};
                      region.srcSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
                      region.dstSubresource = region.srcSubresource;
                      region.extent = {4, 4, 1};
                      vkCmdCopyImage(pc.cmd, pc.image(FrameGraph::previous(history)).image,
                                     VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, pc.image(copy).image,
                                     VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &region);
                  });

    EXPECT_FALSE(graph.hasHistory(history));
    for (int frame = 1; frame <= 3; ++frame) {
        frameValue = float(frame);
        ctx.submitAndWait([&](VkCommandBuffer cmd) { graph.record(cmd); });
        graph.endFrame();
        EXPECT_TRUE(graph.hasHistory(history));
        // After the swap, previous() is what this frame wrote.
        EXPECT_FLOAT_EQ(graph.download(FrameGraph::previous(history))[0], float(frame));
        if (frame >= 2) {
            EXPECT_FLOAT_EQ(graph.download(copy)[0], float(frame - 1));
        }
    }
    graph.resetHistory();
    EXPECT_FALSE(graph.hasHistory(history));
    ASSERT_EQ(graph.timings().size(), 2u);
    EXPECT_EQ(graph.timings()[0].name, "write current");
}

// A pass reaches only the images it declared: the graph derives barriers from the declarations,
// so an image reached around them would be used unsynchronized. The refusal names the pass.
TEST_F(HistoryTest, APassReachesOnlyTheImagesItDeclared) {
    vk::Context& ctx = test::context();
    FrameGraph graph(ctx);
    const VkImageUsageFlags usage = VK_IMAGE_USAGE_TRANSFER_DST_BIT;
    const ImageRef declared =
        graph.createImage("declared", VK_FORMAT_R8G8B8A8_UNORM, {4, 4}, usage);
    const ImageRef other = graph.createImage("other", VK_FORMAT_R8G8B8A8_UNORM, {4, 4}, usage);
    std::string refusal;
    graph.addPass("clear", PassKind::Transfer, {{declared, Use::TransferDst}},
                  [&](const PassContext& pc) {
                      EXPECT_EQ(pc.image(declared).name, "declared");
                      try {
                          pc.image(other);
                      } catch (const std::logic_error& e) {
                          refusal = e.what();
                      }
                  });
    ctx.submitAndWait([&](VkCommandBuffer cmd) { graph.record(cmd); });
    graph.endFrame();
    EXPECT_NE(refusal.find("pass clear"), std::string::npos) << refusal;
    EXPECT_NE(refusal.find("other"), std::string::npos) << refusal;
}

// Two transient images used one after the other share memory on the device: the second's
// first use waits for the first's (synchronization validation would report the hazard), the
// first can no longer be read after the frame unless kept, and a kept one holds its contents.
TEST_F(HistoryTest, TransientImagesTakeTurnsInOneBlockOfMemory) {
    vk::Context& ctx = test::context();
    for (bool keepFirst : {false, true}) {
        FrameGraph graph(ctx);
        const VkImageUsageFlags usage = VK_IMAGE_USAGE_TRANSFER_DST_BIT;
        const ImageRef first =
            graph.createImage("first", VK_FORMAT_R32G32B32A32_SFLOAT, {8, 8}, usage);
        const ImageRef second =
            graph.createImage("second", VK_FORMAT_R32G32B32A32_SFLOAT, {8, 8}, usage);
        auto clearTo = [](ImageRef ref, float value) {
            return [ref, value](const PassContext& pc) {
                VkClearColorValue color{{value, 0, 0, 1}};
                VkImageSubresourceRange range{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
                vkCmdClearColorImage(pc.cmd, pc.image(ref).image,
                                     VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, &color, 1, &range);
            };
        };
        graph.addPass("clear first", PassKind::Transfer, {{first, Use::TransferDst}},
                      clearTo(first, 1.0f));
        graph.addPass("clear second", PassKind::Transfer, {{second, Use::TransferDst}},
                      clearTo(second, 2.0f));
        if (keepFirst) graph.keep(first);
        for (int frame = 0; frame < 2; ++frame) {
            ctx.submitAndWait([&](VkCommandBuffer cmd) { graph.record(cmd); });
            graph.endFrame();
        }
        EXPECT_FLOAT_EQ(graph.download(second)[0], 2.0f);
        if (keepFirst) {
            EXPECT_EQ(graph.sharedMemory().bytes, 2 * graph.image(first).memorySize);
            EXPECT_FLOAT_EQ(graph.download(first)[0], 1.0f);
            continue;
        }
        EXPECT_EQ(graph.sharedMemory().bytes, graph.image(first).memorySize) << "one image's worth";
        EXPECT_EQ(graph.sharedMemory().images.size(), 2u);
        try {
            graph.download(first);
            ADD_FAILURE() << "read although the second image wrote over it";
        } catch (const std::logic_error& e) {
            EXPECT_NE(std::string(e.what()).find("first shares its memory with second"),
                      std::string::npos)
                << e.what();
        }
    }
}

// Timestamps: on a CPU device (lavapipe) a full barrier follows every stamp, so the
// stamp is written where it stands; a GPU records the stamps alone. Checked on what the graph
// recorded, in both modes, on the real device; no timing is judged here.
class TimestampTest : public test::VulkanTest {
protected:
    std::vector<RecordedCommand> recordTwoPasses(TimestampMode mode) {
        vk::Context& ctx = test::context();
        FrameGraph graph(ctx, mode);
        graph.setRecordingLog(true);
        const ImageRef image = graph.createImage("cleared", VK_FORMAT_R32G32B32A32_SFLOAT, {4, 4},
                                                 VK_IMAGE_USAGE_TRANSFER_DST_BIT);
        auto clear = [&](const PassContext& pc) {
            VkClearColorValue value{{1, 0, 0, 1}};
            VkImageSubresourceRange range{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
            vkCmdClearColorImage(pc.cmd, pc.image(image).image,
                                 VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, &value, 1, &range);
        };
        graph.addPass("first", PassKind::Transfer, {{image, Use::TransferDst}}, clear);
        graph.addPass("off", PassKind::Transfer, {{image, Use::TransferDst}}, clear,
                      [](const FrameState&) { return false; });
        graph.addPass("second", PassKind::Transfer, {{image, Use::TransferDst}}, clear);
        ctx.submitAndWait([&](VkCommandBuffer cmd) { graph.record(cmd); });
        graph.endFrame();
        timings = graph.timings();
        return graph.lastCommands();
    }
    std::vector<PassTiming> timings;
};

TEST_F(TimestampTest, TheModeFollowsTheDeviceType) {
    EXPECT_EQ(timestampModeFor(VK_PHYSICAL_DEVICE_TYPE_CPU), TimestampMode::BarrierAfterEach);
    for (VkPhysicalDeviceType gpu :
         {VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU, VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU,
          VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU})
        EXPECT_EQ(timestampModeFor(gpu), TimestampMode::AsRecorded);
    // This suite's device is lavapipe, and the graph picks the mode from it by default.
    FrameGraph graph(test::context());
    EXPECT_EQ(graph.timestampMode(), timestampModeFor(test::context().properties.deviceType));
}

TEST_F(TimestampTest, ACpuDeviceGetsABarrierRightAfterEveryStamp) {
    const std::vector<RecordedCommand> commands = recordTwoPasses(TimestampMode::BarrierAfterEach);
    size_t stamps = 0;
    for (size_t i = 0; i < commands.size(); ++i) {
        if (commands[i].kind != RecordedCommand::Kind::Timestamp) continue;
        ++stamps;
        ASSERT_LT(i + 1, commands.size());
        EXPECT_EQ(commands[i + 1].kind, RecordedCommand::Kind::TimestampBarrier)
            << "stamp of " << commands[i].pass;
    }
    EXPECT_EQ(stamps, 4u) << "a begin and an end stamp for each pass that ran";
}

TEST_F(TimestampTest, AGpuGetsTheStampsAlone) {
    const std::vector<RecordedCommand> commands = recordTwoPasses(TimestampMode::AsRecorded);
    size_t stamps = 0;
    for (const RecordedCommand& c : commands) {
        EXPECT_NE(c.kind, RecordedCommand::Kind::TimestampBarrier) << c.pass;
        stamps += c.kind == RecordedCommand::Kind::Timestamp;
    }
    EXPECT_EQ(stamps, 4u);
    // Each pass: its image barrier, then its record between its two stamps.
    using K = RecordedCommand::Kind;
    const K expected[] = {K::Barrier, K::Timestamp, K::Pass, K::Timestamp,
                          K::Barrier, K::Timestamp, K::Pass, K::Timestamp};
    ASSERT_EQ(commands.size(), std::size(expected));
    for (size_t i = 0; i < commands.size(); ++i)
        EXPECT_EQ(commands[i].kind, expected[i]) << i;
    EXPECT_EQ(commands[6].pass, "second");
}

TEST_F(TimestampTest, PassesAreTimedInOrderAndATurnedOffPassSpansNothing) {
    recordTwoPasses(TimestampMode::BarrierAfterEach);
    ASSERT_EQ(timings.size(), 3u);
    EXPECT_TRUE(timings[0].ran);
    EXPECT_FALSE(timings[1].ran);
    EXPECT_EQ(timings[1].milliseconds, 0.0);
    EXPECT_EQ(timings[0].startMs, 0.0) << "times count from the frame's first stamp";
    EXPECT_LE(timings[0].endMs, timings[2].startMs);
    EXPECT_LE(timings[2].startMs, timings[2].endMs);
}

} // namespace
