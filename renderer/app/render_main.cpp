// render: loads a scene, renders frames on the Vulkan device, writes the image (PNG + EXR) and
// reports per-pass GPU timings.
#include "app/cli.h"
#include "image_io.h"
#include "renderer.h"
#include "scene/animation.h"

#include <nlohmann/json.hpp>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <unistd.h>

namespace fs = std::filesystem;
using namespace ssgi;

namespace {

const char* kUsage = R"(usage: render [SCENE] [options]
  --frames N            frames to render (default 1, or 2 with a profile: one warm-up frame
                        and one timed); the image is the last frame's
  --output FILE.png     tonemapped sRGB image (default out/<scene>.png); the linear HDR image
                        (or the view's linear quantity) goes beside it as FILE.exr
  --view NAME           what the image shows in place of the final image (the views below;
                        contact: in red what contact shadows darkened; peel: the distance to
                        the second depth layer; docs/effects.md)
  --time T              time in seconds along the scene's camera path and object paths
  --profile             print per-pass GPU milliseconds (median, min, max over the timed
                        frames) beside the host clock, and warn where they disagree
  --profile-json FILE   write the timings, device and driver as JSON
  --profile-trace FILE  write a Chrome/Perfetto trace (.json): GPU passes and host frames,
                        every frame, warm-up ones marked (open in ui.perfetto.dev)
  --warmup W            frames left out of the timings (default 1 when more than one frame is
                        rendered: the first compiles shader variants and starts the caches)
  --memory              print the device memory of every image of the frame (after the
                        frames), the block the transient ones share, and what is held in all
  --list-settings       print every method setting (type, default, range, meaning) as the
                        table in docs/settings.md, and exit
)";

struct Args {
    cli::CommonArgs common;
    std::string output, view = "final", profileJson, profileTrace;
    uint32_t frames = 0, warmup = UINT32_MAX; // 0, UINT32_MAX: not given
    float time = -1.0f;
    bool profile = false, memory = false;
    bool profiling() const { return profile || !profileJson.empty() || !profileTrace.empty(); }
};

Args parseArgs(int argc, char** argv) {
    Args a;
    for (int i = 1; i < argc; ++i) {
        const std::string arg = argv[i];
        if (arg == "--help" || arg == "-h") {
            std::cout << kUsage << cli::kCommonUsage << "views:";
            for (const std::string& view : viewNames())
                std::cout << " " << view;
            std::cout << "\n";
            std::exit(0);
        } else if (arg == "--memory") {
            a.memory = true;
        } else if (arg == "--list-settings") {
            std::cout << settingsMarkdown();
            std::exit(0);
        } else if (arg == "--frames") {
            a.frames = cli::parsePositiveCount(arg, cli::optionValue(argc, argv, i));
        } else if (arg == "--output") {
            a.output = cli::optionValue(argc, argv, i);
        } else if (arg == "--view") {
            a.view = cli::optionValue(argc, argv, i);
        } else if (arg == "--time") {
            a.time = float(cli::parseNumber(arg, cli::optionValue(argc, argv, i), 0.0, 1e9));
        } else if (arg == "--profile") {
            a.profile = true;
        } else if (arg == "--profile-json") {
            a.profileJson = cli::optionValue(argc, argv, i);
        } else if (arg == "--profile-trace") {
            a.profileTrace = cli::optionValue(argc, argv, i);
            if (fs::path(a.profileTrace).extension() != ".json")
                throw InputError("--profile-trace: '" + a.profileTrace + "' must end in .json");
        } else if (arg == "--warmup") {
            a.warmup = cli::parseCount(arg, cli::optionValue(argc, argv, i));
        } else if (!cli::parseCommonArg(argc, argv, i, a.common)) {
            throw InputError("unknown option " + arg + " (see render --help)");
        }
    }
    cli::finishCommonArgs(a.common);
    if (a.frames == 0) a.frames = a.profiling() && a.warmup != 0 ? 2 : 1;
    if (a.warmup == UINT32_MAX) a.warmup = a.frames > 1 ? 1 : 0;
    if (a.warmup >= a.frames)
        throw InputError("--warmup " + std::to_string(a.warmup) + " leaves none of the " +
                         std::to_string(a.frames) + " frames to time");
    if (a.output.empty()) a.output = "out/" + fs::path(a.common.scene).stem().string() + ".png";
    if (fs::path(a.output).extension() != ".png")
        throw InputError("--output: '" + a.output + "' must end in .png");
    return a;
}

// What the frame graph holds, image by image (a pair as two), the transient images that share
// one block marked; then what it holds in all.
void printMemory(const graph::FrameGraph& graph, uint32_t width, uint32_t height) {
    const graph::FrameGraph::SharedMemory shared = graph.sharedMemory();
    const auto isShared = [&](const std::string& name) {
        return std::find(shared.images.begin(), shared.images.end(), name) != shared.images.end();
    };
    constexpr double MiB = 1048576.0;
    double total = 0.0;
    for (const auto& [name, bytes, pair] : graph.imageMemory()) {
        std::printf("%-34s %9.1f MiB%s\n", name.c_str(), double(bytes) / MiB,
                    isShared(name) ? "  (shared)" : "");
        total += double(bytes);
    }
    std::printf("%-34s %9.1f MiB (%ux%u)\n", "all images", total / MiB, width, height);
    std::printf("%-34s %9.1f MiB: %zu transient images in one block where their lifetimes in "
                "the frame do not overlap\n",
                "shared block", double(shared.bytes) / MiB, shared.images.size());
    std::printf("%-34s %9.1f MiB\n", "held", double(graph.heldMemory()) / MiB);
}

int run(int argc, char** argv) {
    const Args args = parseArgs(argc, argv);
    const cli::CommonArgs& common = args.common;
    const Scene scene = cli::loadSceneWithSettings(common);
    const std::string exrPath = fs::path(args.output).replace_extension(".exr").string();
    // No output over an input or over another output, before any work.
    std::vector<RunFile> outputs = {{"--output", args.output},
                                    {"the EXR beside --output", exrPath}};
    if (!args.profileJson.empty()) outputs.push_back({"--profile-json", args.profileJson});
    if (!args.profileTrace.empty()) outputs.push_back({"--profile-trace", args.profileTrace});
    checkRunFiles(cli::sceneInputs(scene), outputs);
    vk::Context ctx({common.validation, common.device});
    Renderer renderer(ctx, scene, {common.width, common.height, args.view});
    Camera camera = scene.camera;
    if (args.time >= 0.0f) {
        camera = cameraAtTime(scene, args.time, common.scene);
        renderer.setTime(args.time);
    }

    ProfileLog log(args.warmup);
    // Many frames take long (a million is hours on a CPU device): on a terminal, say how far.
    const bool progress = args.frames > 1 && isatty(fileno(stderr));
    const auto start = std::chrono::steady_clock::now();
    auto lastShown = start;
    for (uint32_t f = 0; f < args.frames; ++f) {
        renderer.renderFrame(camera);
        // Kept only for the profile's output: a million frames' timings would not fit.
        if (args.profiling()) log.add(renderer.lastFrameProfile());
        const auto now = std::chrono::steady_clock::now();
        if (progress &&
            (now - lastShown > std::chrono::milliseconds(500) || f + 1 == args.frames)) {
            lastShown = now;
            const double seconds = std::chrono::duration<double>(now - start).count();
            const double left = seconds / (f + 1) * (args.frames - f - 1);
            std::fprintf(stderr, "\rframe %u of %u, %.0f s, about %.0f s left   ", f + 1,
                         args.frames, seconds, left);
            if (f + 1 == args.frames) std::fprintf(stderr, "\n");
        }
    }

    const std::vector<float> ldr = renderer.readImage("ldr"), hdr = renderer.readImage("hdr");
    writeImages({{args.output, common.width, common.height, &ldr},
                 {exrPath, common.width, common.height, &hdr}}); // both or neither
    std::printf("wrote %s and %s (%ux%u, %u frame%s, scene %s)\n", args.output.c_str(),
                exrPath.c_str(), common.width, common.height, args.frames,
                args.frames == 1 ? "" : "s", common.scene.c_str());

    // The world cache's counters of the last frame, read back once. A table too small for the
    // view leaves pixels without a bounce: said whether profiled or not.
    const auto world = renderer.worldCacheCounts();
    if (world && world->full > 0)
        std::fprintf(stderr,
                     "warning: the world cache's table (%u entries) had no free entry for %u "
                     "pixels of the last frame, which have no bounce: raise world_table_bits\n",
                     world->entries, world->full);
    if (args.memory) printMemory(renderer.frameGraph(), common.width, common.height);
    const std::string device = std::string(ctx.properties.deviceName) + " (" + ctx.driverName + ")";
    if (args.profile) std::printf("%s", log.table(device).c_str());
    if (args.profile && world) {
        const WorldGridPlacement& grid = renderer.worldGrid();
        std::printf("world cache (last frame): %u cells live of %u entries, %u filled, %u "
                    "refreshed, %u evicted, %u pixels without a free entry",
                    world->live, world->entries, world->filled, world->refreshed, world->evicted,
                    world->full);
        if (scene.settings.world_half_res)
            std::printf(", %u pixels looked up alone (no half-res sample on their surface)",
                        world->edges);
        if (world->cut > 0)
            std::printf(", %u gather samples left out (the device's loop limit)", world->cut);
        std::printf("; voxel grid %dx%dx%d of side %.4g\n", grid.size.x, grid.size.y, grid.size.z,
                    double(grid.voxel));
    }
    if (!args.profileJson.empty()) {
        const ProfileSummary summary = log.summary();
        nlohmann::json passes = nlohmann::json::array();
        double total = 0.0;
        for (const PassStatistics& s : summary.passes) {
            passes.push_back({{"name", s.name},
                              {"median_ms", s.medianMs},
                              {"min_ms", s.minMs},
                              {"max_ms", s.maxMs},
                              {"frames_ms", s.framesMs},
                              {"median_invocations", s.medianInvocations},
                              {"frames_invocations", s.framesInvocations}});
            total += s.medianMs;
        }
        nlohmann::json j = {{"scene", common.scene},
                            {"device", ctx.properties.deviceName},
                            {"driver", ctx.driverName},
                            {"width", common.width},
                            {"height", common.height},
                            {"frames", args.frames},
                            {"warmup_frames", summary.warmupFrames},
                            {"passes", passes},
                            {"total_median_ms", total},
                            {"median_invocations", summary.passSum.medianInvocations},
                            {"sum_of_passes_median_ms", summary.passSum.medianMs},
                            {"host_median_ms", summary.host.medianMs},
                            {"host_frames_ms", summary.host.framesMs},
                            {"worst_coverage", summary.worstCoverage}};
        cli::writeTextAtomically(args.profileJson, j.dump(2) + "\n");
    }
    if (!args.profileTrace.empty())
        cli::writeTextAtomically(args.profileTrace, log.traceJson("render", device));
    return cli::validationStatus(ctx.validationMessageCount());
}

} // namespace

int main(int argc, char** argv) {
    return ssgi::cli::guardedMain(argc, argv, run);
}
