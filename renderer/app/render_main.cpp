// render: loads a scene, renders frames on the Vulkan device, writes the image (PNG + EXR) and
// reports per-pass GPU timings.
#include "image_io.h"
#include "renderer.h"
#include "scene/camera.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <unistd.h>

namespace fs = std::filesystem;
using namespace ssgi;

namespace {

const char* kUsage = R"(usage: render [SCENE] [options]
  SCENE                 scene file (.json) or glTF (.gltf/.glb); default scenes/cornell-box.json
  --size WxH            image size (default 512x512)
  --frames N            frames to render (default 1); timings are medians after the first
  --output FILE.png     tonemapped sRGB image (default out/<scene>.png); the linear HDR image
                        goes beside it as FILE.exr
  --view NAME           final, albedo, normal, depth, direct, rsm-flux, rsm-normal
  --time T              camera-path time in seconds (scenes with a camera_path)
  --set KEY=VALUE       override a method setting (repeatable; see the README's settings)
  --profile             print a table of per-pass GPU milliseconds
  --profile-json FILE   write the timings, device and driver as JSON
  --device NAME         use the Vulkan device whose name contains NAME (or SSGI_DEVICE)
  --validation          enable the Khronos validation layer with synchronization validation
                        (or SSGI_VALIDATION=1); any message makes the exit status non-zero
)";

struct Args {
    std::string scene, output, view = "final", profileJson, device;
    uint32_t width = 512, height = 512, frames = 1;
    float time = -1.0f;
    bool profile = false, validation = false;
    std::vector<std::pair<std::string, double>> settings; // --set, checked after loading
};

uint32_t parseCount(const std::string& option, const std::string& text) {
    char* end = nullptr;
    long long v = std::strtoll(text.c_str(), &end, 10);
    if (text.empty() || *end != '\0' || v < 0 || v > 1000000)
        throw InputError(option + ": '" + text + "' is not a whole number in 0..1000000");
    return uint32_t(v);
}

Args parseArgs(int argc, char** argv) {
    Args a;
    auto value = [&](int& i) -> std::string {
        if (i + 1 >= argc) throw InputError(std::string(argv[i]) + " needs a value");
        return argv[++i];
    };
    for (int i = 1; i < argc; ++i) {
        std::string arg = argv[i];
        if (arg == "--help" || arg == "-h") {
            std::cout << kUsage;
            std::exit(0);
        } else if (arg == "--size") {
            std::string v = value(i);
            size_t x = v.find('x');
            if (x == std::string::npos) throw InputError("--size: expected WxH, got '" + v + "'");
            a.width = parseCount("--size", v.substr(0, x));
            a.height = parseCount("--size", v.substr(x + 1));
        } else if (arg == "--frames") {
            a.frames = parseCount(arg, value(i));
            if (a.frames == 0) throw InputError("--frames: must be at least 1");
        } else if (arg == "--output") {
            a.output = value(i);
        } else if (arg == "--view") {
            a.view = value(i);
        } else if (arg == "--time") {
            std::string v = value(i);
            char* end = nullptr;
            a.time = std::strtof(v.c_str(), &end);
            if (v.empty() || *end != '\0' || !(a.time >= 0.0f))
                throw InputError("--time: '" + v + "' is not a time >= 0");
        } else if (arg == "--set") {
            std::string v = value(i);
            size_t eq = v.find('=');
            char* end = nullptr;
            double number = eq == std::string::npos ? 0.0 : std::strtod(v.c_str() + eq + 1, &end);
            if (eq == std::string::npos || eq + 1 == v.size() || *end != '\0')
                throw InputError("--set: expected KEY=NUMBER, got '" + v + "'");
            a.settings.push_back({v.substr(0, eq), number});
        } else if (arg == "--profile") {
            a.profile = true;
        } else if (arg == "--profile-json") {
            a.profileJson = value(i);
        } else if (arg == "--device") {
            a.device = value(i);
        } else if (arg == "--validation") {
            a.validation = true;
        } else if (arg.rfind("--", 0) == 0) {
            throw InputError("unknown option " + arg + " (see render --help)");
        } else if (a.scene.empty()) {
            a.scene = arg;
        } else {
            throw InputError("more than one scene given: " + a.scene + " and " + arg);
        }
    }
    if (a.scene.empty()) {
        a.scene = "scenes/cornell-box.json";
        if (!fs::exists(a.scene))
            a.scene = std::string(SSGI_SOURCE_DIR) + "/scenes/cornell-box.json";
    }
    if (a.output.empty()) a.output = "out/" + fs::path(a.scene).stem().string() + ".png";
    if (fs::path(a.output).extension() != ".png")
        throw InputError("--output: '" + a.output + "' must end in .png");
    if (const char* env = std::getenv("SSGI_DEVICE"); env && a.device.empty()) a.device = env;
#ifndef NDEBUG
    a.validation = true; // debug builds always validate
#endif
    if (const char* env = std::getenv("SSGI_VALIDATION"); env && std::string(env) == "1")
        a.validation = true;
    return a;
}

double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v.empty() ? 0.0 : v[v.size() / 2];
}

void writeTextAtomically(const std::string& path, const std::string& text) {
    const fs::path target(path);
    if (target.has_parent_path()) fs::create_directories(target.parent_path());
    const fs::path tmp = target.parent_path() /
                         (".tmp-" + std::to_string(getpid()) + "-" + target.filename().string());
    {
        std::ofstream out(tmp);
        out << text;
        if (!out) throw InputError(path + ": cannot write");
    }
    fs::rename(tmp, target);
}

int run(int argc, char** argv) {
    Args args = parseArgs(argc, argv);
    Scene scene = loadScene(args.scene);
    for (const auto& [key, value] : args.settings)
        scene.settings[key] = checkSetting("--set", key, value);
    vk::Context ctx({args.validation, args.device});
    Renderer renderer(ctx, scene, {args.width, args.height, args.view});

    Camera camera = scene.camera;
    if (args.time >= 0.0f) {
        if (scene.cameraPath.empty())
            throw InputError(args.scene + ": --time given but the scene has no camera_path");
        camera = cameraAt(scene.cameraPath, args.time);
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
    writeImage(args.output, args.width, args.height, renderer.readImage("ldr"));
    writeImage(exrPath, args.width, args.height, renderer.readImage("hdr"));
    std::printf("wrote %s and %s (%ux%u, %u frame%s, scene %s)\n", args.output.c_str(),
                exrPath.c_str(), args.width, args.height, args.frames, args.frames == 1 ? "" : "s",
                args.scene.c_str());

    double total = 0.0;
    nlohmann::json passes = nlohmann::json::array();
    for (const auto& name : passNames) {
        const double ms = median(perPass[name]);
        total += ms;
        passes.push_back({{"name", name}, {"median_ms", ms}, {"frames_ms", perPass[name]}});
    }
    if (args.profile) {
        std::printf("device: %s (%s)\n", ctx.properties.deviceName, ctx.driverName.c_str());
        std::printf("%-12s %10s\n", "pass", "GPU ms");
        for (const auto& p : passes)
            std::printf("%-12s %10.3f\n", p["name"].get<std::string>().c_str(),
                        p["median_ms"].get<double>());
        std::printf("%-12s %10.3f  (median over %zu frame%s)\n", "total", total,
                    perPass.empty() ? size_t(0) : perPass.begin()->second.size(),
                    args.frames > 2 ? "s" : "");
    }
    if (!args.profileJson.empty()) {
        nlohmann::json j = {{"scene", args.scene},      {"device", ctx.properties.deviceName},
                            {"driver", ctx.driverName}, {"width", args.width},
                            {"height", args.height},    {"frames", args.frames},
                            {"passes", passes},         {"total_median_ms", total}};
        writeTextAtomically(args.profileJson, j.dump(2) + "\n");
    }
    if (ctx.validationMessageCount() > 0) {
        std::fprintf(stderr, "error: the validation layer reported %u message(s)\n",
                     ctx.validationMessageCount());
        return 1;
    }
    return 0;
}

} // namespace

int main(int argc, char** argv) {
    try {
        return run(argc, argv);
    } catch (const InputError& e) {
        std::fprintf(stderr, "error: %s\n", e.what());
        return 2;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "error: %s\n", e.what());
        return 1;
    }
}
