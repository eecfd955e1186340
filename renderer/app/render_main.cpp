// render: loads a scene, renders frames on the Vulkan device, writes the image (PNG + EXR) and
// reports per-pass GPU timings.
#include "app/cli.h"
#include "image_io.h"
#include "renderer.h"
#include "scene/camera.h"

#include <nlohmann/json.hpp>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <map>

namespace fs = std::filesystem;
using namespace ssgi;

namespace {

const char* kUsage = R"(usage: render [SCENE] [options]
  --frames N            frames to render (default 1); timings are medians after the first
  --output FILE.png     tonemapped sRGB image (default out/<scene>.png); the linear HDR image
                        (or the view's linear quantity) goes beside it as FILE.exr
  --view NAME           final, albedo, normal, depth, direct, rsm-flux, rsm-normal, shadow,
                        ao, indirect, ssdo, contact (red: what contact shadows darkened),
                        peel (distance to the second depth layer)
  --time T              time in seconds along the scene's camera path and object paths
  --profile             print a table of per-pass GPU milliseconds
  --profile-json FILE   write the timings, device and driver as JSON
)";

struct Args {
    cli::CommonArgs common;
    std::string output, view = "final", profileJson;
    uint32_t frames = 1;
    float time = -1.0f;
    bool profile = false;
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
        } else if (arg == "--output") {
            a.output = cli::optionValue(argc, argv, i);
        } else if (arg == "--view") {
            a.view = cli::optionValue(argc, argv, i);
        } else if (arg == "--time") {
            std::string v = cli::optionValue(argc, argv, i);
            char* end = nullptr;
            a.time = std::strtof(v.c_str(), &end);
            if (v.empty() || *end != '\0' || !(a.time >= 0.0f))
                throw InputError("--time: '" + v + "' is not a time >= 0");
        } else if (arg == "--profile") {
            a.profile = true;
        } else if (arg == "--profile-json") {
            a.profileJson = cli::optionValue(argc, argv, i);
        } else if (!cli::parseCommonArg(argc, argv, i, a.common)) {
            throw InputError("unknown option " + arg + " (see render --help)");
        }
    }
    cli::finishCommonArgs(a.common);
    if (a.output.empty()) a.output = "out/" + fs::path(a.common.scene).stem().string() + ".png";
    if (fs::path(a.output).extension() != ".png")
        throw InputError("--output: '" + a.output + "' must end in .png");
    return a;
}

int run(int argc, char** argv) {
    const Args args = parseArgs(argc, argv);
    const cli::CommonArgs& common = args.common;
    const Scene scene = cli::loadSceneWithSettings(common);
    vk::Context ctx({common.validation, common.device});
    Renderer renderer(ctx, scene, {common.width, common.height, args.view});

    Camera camera = scene.camera;
    if (args.time >= 0.0f) {
        if (scene.cameraPath.empty() && scene.objectPaths.empty())
            throw InputError(common.scene +
                             ": --time given but the scene has no camera_path or object_paths");
        if (!scene.cameraPath.empty()) camera = cameraAt(scene.cameraPath, args.time);
        renderer.setTime(args.time);
    }

    // Per pass, its milliseconds in each frame after the first (warm-up) frame.
    std::vector<std::string> passNames;
    std::map<std::string, std::vector<double>> perPass;
    for (uint32_t f = 0; f < args.frames; ++f) {
        renderer.renderFrame(camera);
        if (f == 0 && args.frames > 1) continue;
        for (const auto& t : renderer.timings()) {
            if (!perPass.count(t.name)) passNames.push_back(t.name);
            perPass[t.name].push_back(t.milliseconds);
        }
    }

    const std::string exrPath = fs::path(args.output).replace_extension(".exr").string();
    writeImage(args.output, common.width, common.height, renderer.readImage("ldr"));
    writeImage(exrPath, common.width, common.height, renderer.readImage("hdr"));
    std::printf("wrote %s and %s (%ux%u, %u frame%s, scene %s)\n", args.output.c_str(),
                exrPath.c_str(), common.width, common.height, args.frames,
                args.frames == 1 ? "" : "s", common.scene.c_str());

    double total = 0.0;
    nlohmann::json passes = nlohmann::json::array();
    for (const auto& name : passNames) {
        const double ms = cli::median(perPass[name]);
        total += ms;
        passes.push_back({{"name", name}, {"median_ms", ms}, {"frames_ms", perPass[name]}});
    }
    if (args.profile) {
        std::printf("device: %s (%s)\n", ctx.properties.deviceName, ctx.driverName.c_str());
        std::printf("%-18s %10s\n", "pass", "GPU ms");
        for (const auto& p : passes)
            std::printf("%-18s %10.3f\n", p["name"].get<std::string>().c_str(),
                        p["median_ms"].get<double>());
        const size_t counted = perPass.empty() ? 0 : perPass.begin()->second.size();
        std::printf("%-18s %10.3f  (median over %zu frame%s)\n", "total", total, counted,
                    counted == 1 ? "" : "s");
    }
    if (!args.profileJson.empty()) {
        nlohmann::json j = {{"scene", common.scene},    {"device", ctx.properties.deviceName},
                            {"driver", ctx.driverName}, {"width", common.width},
                            {"height", common.height},  {"frames", args.frames},
                            {"passes", passes},         {"total_median_ms", total}};
        cli::writeTextAtomically(args.profileJson, j.dump(2) + "\n");
    }
    return cli::validationStatus(ctx.validationMessageCount());
}

} // namespace

int main(int argc, char** argv) {
    return ssgi::cli::guardedMain(argc, argv, run);
}
