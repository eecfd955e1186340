// viewer: the renderer in a desktop window with a panel of settings, timings and debug views.
// Scripted runs (--frames) drive it without a person, for tests and figures.
#include "app/cli.h"
#include "viewer/viewer.h"

#include <algorithm>
#include <cstdlib>
#include <iostream>
#include <iterator>

using namespace ssgi;

namespace {

const char* kUsage = R"(usage: viewer [SCENE] [options]
  Interactive: W/A/S/D/Q/E fly (Shift faster), right drag turns, Ctrl + left drag moves the
  light over the floor (Ctrl + Shift: up and down), Tab hides the panel, F12 writes a
  screenshot to out/, Esc quits.
  --size WxH            window size (default 1280x720)
  --render-scale F      renderer resolution relative to the image area (default 1; 0.5 is
                        four times fewer pixels, for software devices)
  --view NAME           the composite's view to start with (see render --help)
  --cache-view NAME     start with a view of the cache: confidence, disocclusion, converged,
                        refreshed-tile (of --effect, default ao)
  --effect NAME         the cached effect the cache views show (shadow, ao, ssdo, indirect,
                        sky_visibility)
Scripted runs:
  --frames N            stop after N frames
  --play-path           follow the scene's camera path (over the N frames, or in real time)
  --path-step S         path seconds per frame instead
  --resize-at K WxH     resize the window after frame K
  --screenshot FILE.png the whole window (image and panel) after the last frame
  --report FILE.json    per frame: window and image sizes, GPU ms, history counts; validation
  --record-into FILE    record the camera every frame and write the scene with that
                        camera_path to FILE (.json)
)";

VkExtent2D parseSize(const std::string& option, const std::string& v) {
    const size_t x = v.find('x');
    if (x == std::string::npos) throw InputError(option + ": expected WxH, got '" + v + "'");
    const uint32_t w = cli::parseCount(option, v.substr(0, x));
    const uint32_t h = cli::parseCount(option, v.substr(x + 1));
    if (w == 0 || h == 0 || w > 16384 || h > 16384)
        throw InputError(option + ": " + v + " is outside 1x1..16384x16384");
    return {w, h};
}

viewer::ViewerOptions parseArgs(int argc, char** argv) {
    viewer::ViewerOptions o;
    o.common.width = 1280;
    o.common.height = 720;
    for (int i = 1; i < argc; ++i) {
        const std::string arg = argv[i];
        if (arg == "--help" || arg == "-h") {
            std::cout << kUsage << cli::kCommonUsage;
            std::exit(0);
        } else if (arg == "--frames") {
            o.frames = cli::parsePositiveCount(arg, cli::optionValue(argc, argv, i));
        } else if (arg == "--play-path") {
            o.playPath = true;
        } else if (arg == "--path-step") {
            const std::string v = cli::optionValue(argc, argv, i);
            char* end = nullptr;
            o.pathStep = std::strtof(v.c_str(), &end);
            if (v.empty() || *end != '\0' || !(o.pathStep > 0.0f && o.pathStep < 1e6f))
                throw InputError("--path-step: '" + v + "' is not a time > 0");
        } else if (arg == "--resize-at") {
            o.resizeAt = cli::parseCount(arg, cli::optionValue(argc, argv, i));
            o.resizeTo = parseSize(arg, cli::optionValue(argc, argv, i));
        } else if (arg == "--render-scale") {
            const std::string v = cli::optionValue(argc, argv, i);
            char* end = nullptr;
            o.renderScale = std::strtof(v.c_str(), &end);
            if (v.empty() || *end != '\0' || !(o.renderScale >= 0.05f && o.renderScale <= 4.0f))
                throw InputError("--render-scale: '" + v + "' is not in 0.05..4");
        } else if (arg == "--view") {
            o.view = cli::optionValue(argc, argv, i);
        } else if (arg == "--cache-view") {
            o.cacheView = cli::optionValue(argc, argv, i);
        } else if (arg == "--effect") {
            o.cacheEffect = cli::optionValue(argc, argv, i);
            const std::string effects[] = {"shadow", "ao", "ssdo", "indirect", "sky_visibility"};
            if (std::find(std::begin(effects), std::end(effects), o.cacheEffect) ==
                std::end(effects))
                throw InputError("--effect: unknown effect '" + o.cacheEffect +
                                 "' (shadow, ao, ssdo, indirect, sky_visibility)");
        } else if (arg == "--screenshot") {
            o.screenshot = cli::optionValue(argc, argv, i);
            if (o.screenshot.size() < 4 || o.screenshot.substr(o.screenshot.size() - 4) != ".png")
                throw InputError("--screenshot: '" + o.screenshot + "' must end in .png");
        } else if (arg == "--report") {
            o.report = cli::optionValue(argc, argv, i);
        } else if (arg == "--record-into") {
            o.recordInto = cli::optionValue(argc, argv, i);
        } else if (arg == "--size") {
            const VkExtent2D size = parseSize(arg, cli::optionValue(argc, argv, i));
            o.common.width = size.width;
            o.common.height = size.height;
        } else if (!cli::parseCommonArg(argc, argv, i, o.common)) {
            throw InputError("unknown option " + arg + " (see viewer --help)");
        }
    }
    cli::finishCommonArgs(o.common);
    if (o.frames == 0 && (!o.screenshot.empty() || !o.report.empty()))
        throw InputError("--screenshot and --report need --frames (a scripted run)");
    return o;
}

int run(int argc, char** argv) {
    viewer::Viewer v(parseArgs(argc, argv));
    return v.run();
}

} // namespace

int main(int argc, char** argv) {
    return cli::guardedMain(argc, argv, run);
}
