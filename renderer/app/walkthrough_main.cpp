// walkthrough: renders a scene's camera path frame by frame, with the temporal cache on or off,
// and writes every frame's per-pass GPU timings (CSV or JSON) and, on request, the frames.
#include "app/cli.h"
#include "image_io.h"
#include "renderer.h"
#include "scene/camera.h"

#include <nlohmann/json.hpp>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <sstream>
#include <unistd.h>

namespace fs = std::filesystem;
using namespace ssgi;

namespace {

const char* kUsage = R"(usage: walkthrough SCENE [options]
  --frames N            frames along the camera path (default 120), evenly spaced in time
  --still               keep the camera at the path's first key, or the scene's camera when
                        it has no path (a still camera)
  --cache 0|1           the temporal cache off or on (default: the scene's setting)
  --timings FILE        per-frame, per-pass GPU milliseconds and the host clock (.csv or .json)
  --profile-trace FILE  a Chrome/Perfetto trace (.json) of every frame: GPU passes and host
  --frames-dir DIR      write every frame as DIR/frame_NNNN.png
  --exr                 with --frames-dir, also DIR/frame_NNNN.exr: the linear radiance (or
                        the view's linear quantity), for measuring frame by frame
  --view NAME           the composite's view in the frames (default final; see render --help)
)";

struct Args {
    cli::CommonArgs common;
    uint32_t frames = 120;
    bool still = false;
    int cache = -1;
    std::string timings, framesDir, view = "final", profileTrace;
    bool exr = false;
};

Args parseArgs(int argc, char** argv) {
    Args a;
    for (int i = 1; i < argc; ++i) {
        const std::string arg = argv[i];
        if (arg == "--help" || arg == "-h") {
            std::cout << kUsage << cli::kCommonUsage;
            std::exit(0);
        } else if (arg == "--frames") {
            a.frames = cli::parsePositiveCount(arg, cli::optionValue(argc, argv, i));
        } else if (arg == "--still") {
            a.still = true;
        } else if (arg == "--cache") {
            const std::string v = cli::optionValue(argc, argv, i);
            if (v != "0" && v != "1") throw InputError("--cache: expected 0 or 1, got '" + v + "'");
            a.cache = v == "1";
        } else if (arg == "--timings") {
            a.timings = cli::optionValue(argc, argv, i);
            const std::string ext = fs::path(a.timings).extension().string();
            if (ext != ".csv" && ext != ".json")
                throw InputError("--timings: '" + a.timings + "' must end in .csv or .json");
        } else if (arg == "--profile-trace") {
            a.profileTrace = cli::optionValue(argc, argv, i);
            if (fs::path(a.profileTrace).extension() != ".json")
                throw InputError("--profile-trace: '" + a.profileTrace + "' must end in .json");
        } else if (arg == "--frames-dir") {
            a.framesDir = cli::optionValue(argc, argv, i);
        } else if (arg == "--exr") {
            a.exr = true;
        } else if (arg == "--view") {
            a.view = cli::optionValue(argc, argv, i);
        } else if (!cli::parseCommonArg(argc, argv, i, a.common)) {
            throw InputError("unknown option " + arg + " (see walkthrough --help)");
        }
    }
    if (a.exr && a.framesDir.empty()) throw InputError("--exr needs --frames-dir");
    if (a.cache >= 0) a.common.settings.push_back({"cache", double(a.cache)});
    cli::finishCommonArgs(a.common);
    return a;
}

// DIR/frame_NNNN.png (or .exr): frame f's file.
std::string framePath(const std::string& dir, uint32_t f, const char* extension) {
    char name[32];
    std::snprintf(name, sizeof name, "frame_%04u%s", f, extension);
    return (fs::path(dir) / name).string();
}

int run(int argc, char** argv) {
    const Args args = parseArgs(argc, argv);
    const cli::CommonArgs& common = args.common;
    const Scene scene = cli::loadSceneWithSettings(common);
    if (scene.cameraPath.empty() && !args.still)
        throw InputError(common.scene + ": the scene has no camera_path to walk (--still "
                                        "renders its camera)");
    // No output over an input or over another output, before any work.
    std::vector<RunFile> outputs;
    if (!args.timings.empty()) outputs.push_back({"--timings", args.timings});
    if (!args.profileTrace.empty()) outputs.push_back({"--profile-trace", args.profileTrace});
    // The frames whose names are taken (a file, a link): a name not taken yet is no input
    // (inputs exist), the timings and the trace end in .csv or .json, and a million frames'
    // names would take hundreds of MB to compare.
    std::vector<const char*> extensions = {".png"};
    if (args.exr) extensions.push_back(".exr");
    for (uint32_t f = 0; !args.framesDir.empty() && f < args.frames; ++f)
        for (const char* extension : extensions) {
            const std::string frame = framePath(args.framesDir, f, extension);
            std::error_code ec;
            if (fs::exists(fs::symlink_status(frame, ec)))
                outputs.push_back({"--frames-dir", frame});
        }
    checkRunFiles(cli::sceneInputs(scene), outputs);
    vk::Context ctx({common.validation, common.device});
    Renderer renderer(ctx, scene, {common.width, common.height, args.view});

    const float duration = scene.cameraPath.empty() ? 0.0f : scene.cameraPath.keys.back().time;
    // Every frame's passes and host clock; the first frame compiles pipelines and starts the
    // caches: the summary leaves it out.
    ProfileLog log(args.frames > 1 ? 1 : 0);
    for (uint32_t f = 0; f < args.frames; ++f) {
        const float t = args.still || args.frames == 1 ? 0.0f : duration * f / (args.frames - 1);
        renderer.setTime(t);
        renderer.renderFrame(scene.cameraPath.empty() ? scene.camera
                                                      : cameraAt(scene.cameraPath, t));
        log.add(renderer.lastFrameProfile());
        if (!args.framesDir.empty()) {
            const std::vector<float> ldr = renderer.readImage("ldr");
            std::vector<float> hdr;
            std::vector<ImageFile> files = {
                {framePath(args.framesDir, f, ".png"), common.width, common.height, &ldr}};
            if (args.exr) {
                hdr = renderer.readImage("hdr");
                files.push_back(
                    {framePath(args.framesDir, f, ".exr"), common.width, common.height, &hdr});
            }
            writeImages(files); // a frame's PNG and EXR land together or not at all
        }
        if (isatty(2))
            std::fprintf(stderr, "\rframe %u/%u  %.1f ms", f + 1, args.frames,
                         log.frames().back().passSumMs());
    }
    if (isatty(2)) std::fprintf(stderr, "\n");

    if (!args.timings.empty()) {
        if (fs::path(args.timings).extension() == ".csv") {
            std::ostringstream csv;
            csv << "frame,pass,ms\n"; // "total": the passes added up; "host": the host clock
            for (uint32_t f = 0; f < args.frames; ++f) {
                const FrameProfile& frame = log.frames()[f];
                for (const PassTiming& pass : frame.passes)
                    csv << f << "," << pass.name << "," << pass.milliseconds << "\n";
                csv << f << ",total," << frame.passSumMs() << "\n";
                csv << f << ",host," << frame.hostMs << "\n";
            }
            cli::writeTextAtomically(args.timings, csv.str());
        } else {
            std::vector<double> totals, host;
            nlohmann::json passes = nlohmann::json::object();
            for (const FrameProfile& frame : log.frames()) {
                totals.push_back(frame.passSumMs());
                host.push_back(frame.hostMs);
                for (const PassTiming& pass : frame.passes)
                    passes[pass.name].push_back(pass.milliseconds);
            }
            nlohmann::json j = {{"scene", common.scene},
                                {"device", ctx.properties.deviceName},
                                {"driver", ctx.driverName},
                                {"width", common.width},
                                {"height", common.height},
                                {"frames", args.frames},
                                {"cache", scene.settings.cache},
                                {"still", args.still},
                                {"total_ms", totals},
                                {"host_ms", host},
                                {"passes", passes}};
            cli::writeTextAtomically(args.timings, j.dump(1) + "\n");
        }
    }

    const std::string device = std::string(ctx.properties.deviceName) + " (" + ctx.driverName + ")";
    if (!args.profileTrace.empty())
        cli::writeTextAtomically(args.profileTrace, log.traceJson("walkthrough", device));
    std::printf("walkthrough of %s: %u frames at %ux%u, cache %s\n", common.scene.c_str(),
                args.frames, common.width, common.height, scene.settings.cache ? "on" : "off");
    std::printf("%s", log.table(device).c_str());
    return cli::validationStatus(ctx.validationMessageCount());
}

} // namespace

int main(int argc, char** argv) {
    return ssgi::cli::guardedMain(argc, argv, run);
}
