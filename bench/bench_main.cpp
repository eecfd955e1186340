// benchmark: measures one scene and writes what it measured as JSON (bench/run.sh runs it for
// every scene and size, bench/report.py draws the charts and tables).
//   benchmark sweep SCENE --out FILE       probe, configurations, cached series, memory
//   benchmark walkthrough SCENE --out FILE the camera path with the cache off and on
//   benchmark indirect SCENE --out FILE    the indirect light's methods: cost and error
//   benchmark cache-fixes SCENE --out FILE the cache's fixes, each undone: path and still camera
#include "app/cli.h"
#include "bench.h"

#include <cstdio>
#include <ctime>
#include <filesystem>
#include <iostream>
#include <sstream>

namespace fs = std::filesystem;
using namespace ssgi;

namespace {

const char* kUsage =
    R"(usage: benchmark sweep|walkthrough|indirect|cache-fixes SCENE --out FILE.json [options]
  --out FILE.json       where the results go (written whole or not at all)
  --error-size N        real-time and reference images for the error are NxN (default 128)
  --warmup N            frames rendered before timing (default 1)
  --frames N            frames timed; medians (default 5)
  --series-frames N     sweep: cached still-camera frames (default 64)
  --path-frames N       walkthrough, cache-fixes: frames along the camera path (default 120)
  --error-frames N      walkthrough, cache-fixes: frames whose error is measured (default 4)
  --still-frames N      cache-fixes: frames of the still camera at the path's end (default 64)
  --spp N               reference samples per pixel, at most (default 16384; each stops at 1%
                        estimated noise)
  --no-error            timing only: no reference, no error renders
  --no-series           sweep: no cached still-camera series
  --series-methods N    sweep: 1 = the thesis rule only, 2 = also the running mean, 3 = also
                        the running mean with cheap frames (default)
  --method "LABEL: K=V ..."  walkthrough: a configuration to compare (repeatable); replaces the
                        default ones (cache off; thesis rule; running mean with cheap frames;
                        world cache, indirect_method 3); indirect: an indirect-light
                        configuration to compare with "off" (replaces the thesis's, the
                        interleaved, the importance and the world cache methods)
  --converged-frames N  indirect: cached still-camera frames of the converged image (default 40)
  --commit TEXT         the source's commit, recorded with the results
)";

struct Args {
    std::string command;
    cli::CommonArgs common;
    bench::Options options;
    std::string out, commit = "unknown";
    uint32_t pathFrames = 120, errorFrames = 4, convergedFrames = 40, stillFrames = 64;
};

// "LABEL: key=value key=value ..." (a walkthrough configuration).
std::pair<std::string, SettingOverrides> parseMethod(const std::string& text) {
    const size_t colon = text.find(':');
    if (colon == std::string::npos || colon == 0)
        throw InputError("--method '" + text + "': expected LABEL: key=value ...");
    std::pair<std::string, SettingOverrides> method{text.substr(0, colon), {}};
    std::istringstream words(text.substr(colon + 1));
    for (std::string word; words >> word;)
        method.second.insert(cli::parseSetting("--method", word));
    return method;
}

Args parseArgs(int argc, char** argv) {
    Args a;
    const std::string command = argc >= 2 ? argv[1] : "";
    if (command == "--help" || command == "-h") {
        std::cout << kUsage << cli::kCommonUsage;
        std::exit(0);
    }
    if (command != "sweep" && command != "walkthrough" && command != "indirect" &&
        command != "cache-fixes")
        throw InputError((command.empty() ? std::string("no command given")
                                          : "unknown command '" + command + "'") +
                         ": the first argument is sweep, walkthrough, indirect or cache-fixes "
                         "(see benchmark --help)");
    a.command = argv[1];
    for (int i = 2; i < argc; ++i) {
        const std::string arg = argv[i];
        auto value = [&] { return cli::optionValue(argc, argv, i); };
        if (arg == "--out")
            a.out = value();
        else if (arg == "--error-size")
            a.options.errorWidth = a.options.errorHeight = cli::parsePositiveCount(arg, value());
        else if (arg == "--warmup")
            a.options.warmup = cli::parseCount(arg, value());
        else if (arg == "--frames")
            a.options.frames = cli::parsePositiveCount(arg, value());
        else if (arg == "--series-frames")
            a.options.seriesFrames = cli::parsePositiveCount(arg, value());
        else if (arg == "--path-frames")
            a.pathFrames = cli::parsePositiveCount(arg, value());
        else if (arg == "--converged-frames")
            a.convergedFrames = cli::parsePositiveCount(arg, value());
        else if (arg == "--still-frames")
            a.stillFrames = cli::parsePositiveCount(arg, value());
        else if (arg == "--error-frames")
            a.errorFrames = cli::parsePositiveCount(arg, value());
        else if (arg == "--spp")
            a.options.referenceSpp = cli::parsePositiveCount(arg, value());
        else if (arg == "--no-error")
            a.options.error = false;
        else if (arg == "--no-series")
            a.options.series = false;
        else if (arg == "--series-methods")
            a.options.seriesMethods = cli::parsePositiveCount(arg, value());
        else if (arg == "--method")
            a.options.methods.push_back(parseMethod(value()));
        else if (arg == "--commit")
            a.commit = value();
        else if (!cli::parseCommonArg(argc, argv, i, a.common))
            throw InputError("unknown option " + arg + " (see benchmark --help)");
    }
    if (a.out.empty() || fs::path(a.out).extension() != ".json")
        throw InputError("--out FILE.json is required");
    cli::finishCommonArgs(a.common);
    a.options.width = a.common.width;
    a.options.height = a.common.height;
    a.errorFrames = std::min(a.errorFrames, a.pathFrames);
    return a;
}

std::string utcNow() {
    char text[32];
    const std::time_t now = std::time(nullptr);
    std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&now));
    return text;
}

int run(int argc, char** argv) {
    const Args args = parseArgs(argc, argv);
    const Scene scene = cli::loadSceneWithSettings(args.common);
    checkRunFiles(cli::sceneInputs(scene), {{"--out", args.out}}); // before any work
    vk::Context ctx({args.common.validation, args.common.device});
    const bench::Options& o = args.options;
    bench::Json j = {{"kind", args.command},
                     {"scene", fs::path(args.common.scene).stem().string()},
                     {"scene_file", args.common.scene},
                     {"device", bench::deviceJson(ctx)},
                     {"commit", args.commit},
                     {"date", utcNow()},
                     {"width", o.width},
                     {"height", o.height},
                     {"error_width", o.errorWidth},
                     {"error_height", o.errorHeight},
                     {"warmup", o.warmup},
                     {"frames", o.frames},
                     {"scene_settings", bench::settingsJson(settingValues(scene.settings))}};
    if (args.command == "sweep") {
        j["series_frames"] = o.series ? o.seriesFrames : 0;
        j.update(bench::sweep(ctx, scene, o));
    } else if (args.command == "indirect") {
        j["indirect"] = bench::indirectComparison(ctx, scene, o, args.convergedFrames);
    } else if (args.command == "cache-fixes") {
        j.update(bench::cacheFixes(ctx, scene, o, args.pathFrames, o.error ? args.errorFrames : 0,
                                   args.stillFrames));
    } else {
        j["walkthrough"] =
            bench::walkthrough(ctx, scene, o, args.pathFrames, o.error ? args.errorFrames : 0);
    }
    if (ctx.validationMessageCount() > 0) {
        std::fprintf(stderr, "error: the validation layer reported %u message(s)\n",
                     ctx.validationMessageCount());
        return 1;
    }
    fs::create_directories(fs::absolute(args.out).parent_path());
    cli::writeTextAtomically(args.out, j.dump(1) + "\n");
    return 0;
}

} // namespace

int main(int argc, char** argv) {
    return cli::guardedMain(argc, argv, run);
}
