// stability: runs the scripted failure cases (renderer/stability/cases.h) and writes a table of
// their figures (Markdown, CSV, JSON), every frame's figures (CSV) and each case's pictures;
// docs/stability_plot.py draws the error over frames from the JSON.
#include "app/cli.h"
#include "image_io.h"
#include "stability/run.h"

#include <nlohmann/json.hpp>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <sstream>

namespace fs = std::filesystem;
using namespace ssgi;
using namespace ssgi::stability;

namespace {

const char* kUsage = R"(usage: stability [CASE...] [options]
  CASE                  run only these cases (default: every case; --list names them)
  --list                print the cases and what fails in each, then exit
  --quick               96x72, 37-frame warm-up, hold and reference, no ground truth: the
                        whole suite in a few minutes on 2 CPU cores
  --truth-spp N         samples per pixel of the path-traced comparison (default 64; 0 = off)
  --out DIR             where the results go (default out/stability)
  --no-plot             do not run docs/stability_plot.py (python3 with matplotlib) afterwards
  --size WxH            image size (default 160x120)
  --set KEY=VALUE       override a method setting (repeatable), e.g. cache_method=1
  --device NAME         use the Vulkan device whose name contains NAME (or SSGI_DEVICE)
  --validation          enable the Khronos validation layer with synchronization validation
)";

struct Args {
    cli::CommonArgs common;
    std::vector<Case> cases;
    RunOptions run;
    std::string out = "out/stability";
    bool plot = true;
};

Args parseArgs(int argc, char** argv) {
    Args a;
    bool quick = false, sizeGiven = false;
    int truthSpp = -1;
    for (int i = 1; i < argc; ++i) {
        const std::string arg = argv[i];
        if (arg == "--help" || arg == "-h") {
            std::cout << kUsage;
            std::exit(0);
        } else if (arg == "--list") {
            for (const Case& c : suite())
                std::printf("%-13s %-36s %s\n", c.name.c_str(), c.scene.c_str(), c.failure.c_str());
            std::exit(0);
        } else if (arg == "--quick") {
            quick = true;
        } else if (arg == "--truth-spp") {
            truthSpp = int(cli::parseCount(arg, cli::optionValue(argc, argv, i)));
        } else if (arg == "--out") {
            a.out = cli::optionValue(argc, argv, i);
        } else if (arg == "--no-plot") {
            a.plot = false;
        } else if (arg.rfind("--", 0) == 0) {
            sizeGiven = sizeGiven || arg == "--size";
            if (!cli::parseCommonArg(argc, argv, i, a.common))
                throw InputError("unknown option " + arg + " (see stability --help)");
        } else {
            a.cases.push_back(findCase(arg));
        }
    }
    cli::finishCommonArgs(a.common);
    if (a.cases.empty()) a.cases = suite();
    if (quick) {
        a.run.width = 96, a.run.height = 72;
        a.run.warmup = a.run.hold = a.run.converge = 37; // one frame past 36 rotations
    }
    a.run.truthSpp = truthSpp >= 0 ? uint32_t(truthSpp) : quick ? 0 : 64;
    // A size of 0 given is checked as any other (it was taken for "not given").
    if (sizeGiven) a.run.width = a.common.width, a.run.height = a.common.height;
    if (a.run.width < 16 || a.run.height < 16)
        throw InputError("--size: at least 16x16 (the regions need a few pixels)");
    for (const auto& [key, value] : a.common.settings)
        a.run.settings.push_back({key, checkSetting("--set", key, value)});
    a.run.repository = cli::dataDirectory(); // where scenes/stability/ is, installed or not
    return a;
}

std::string number(double v, int digits = 4) {
    if (!std::isfinite(v)) return "–";
    char text[32];
    std::snprintf(text, sizeof text, "%.*g", digits, v);
    return text;
}

nlohmann::json finite(double v) {
    return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr);
}

// The case's picture: its panels side by side.
void writeStrip(const std::string& path, const CaseResult& r) {
    const size_t w = r.width, h = r.height, n = r.panels.size();
    std::vector<float> strip(w * n * h * 4, 1.0f);
    for (size_t p = 0; p < n; ++p)
        for (size_t y = 0; y < h; ++y)
            for (size_t x = 0; x < w; ++x)
                for (size_t ch = 0; ch < 3; ++ch)
                    strip[4 * (y * w * n + p * w + x) + ch] = r.panels[p][4 * (y * w + x) + ch];
    writeImage(path, uint32_t(w * n), uint32_t(h), strip);
}

std::string table(const std::vector<CaseResult>& results) {
    std::ostringstream md;
    md << "| case | region (pixels) | NaN/Inf | flicker, still | change per frame, moving | "
          "recovery (frames) | settled error: region / elsewhere (fresh start) | region error "
          "over a fresh "
          "start's | AO history kept | stale light | truth: start / fresh / tested (elsewhere) |\n"
       << "|---|---|---|---|---|---|---|---|---|---|---|\n";
    for (const CaseResult& r : results)
        md << "| " << r.spec.name << " | " << regionName(r.spec.region) << " (" << r.regionPixels
           << ") | " << r.nonFinite << " | " << number(r.stillFlicker, 2) << " | "
           << number(r.pathFlicker, 2) << " | "
           << (r.recoveryFrames < 0 ? std::string("never") : std::to_string(r.recoveryFrames))
           << " | " << number(r.convergedError, 2) << " / " << number(r.restError, 2) << " ("
           << number(r.freshSettledError, 2) << ") | " << number(r.excessOverFresh + 1.0, 3)
           << "× | " << number(r.reusedAtChange, 2) << " | " << number(r.staleAfter, 2) << " | "
           << number(r.truthStart, 3) << " / " << number(r.truthFresh, 3) << " / "
           << number(r.truthEnd, 3) << " (" << number(r.truthRest, 3) << ") |\n";
    return md.str();
}

nlohmann::json toJson(const CaseResult& r) {
    nlohmann::json frames = nlohmann::json::array();
    for (const FrameRecord& f : r.frames)
        frames.push_back({{"phase", f.phase},
                          {"since_change", f.sinceChange},
                          {"flicker", finite(f.flicker)},
                          {"error", finite(f.error)},
                          {"error_rest", finite(f.errorRest)},
                          {"fresh_error", finite(f.freshError)},
                          {"fresh_rest", finite(f.freshRest)},
                          {"stale", finite(f.stale)},
                          {"ao_reused", finite(f.reused)},
                          {"non_finite", f.nonFinite}});
    return {{"case", r.spec.name},
            {"scene", r.spec.scene},
            {"failure", r.spec.failure},
            {"region", regionName(r.spec.region)},
            {"region_pixels", r.regionPixels},
            {"width", r.width},
            {"height", r.height},
            {"non_finite", r.nonFinite},
            {"non_finite_images", r.nonFiniteImages},
            {"flicker_still", finite(r.stillFlicker)},
            {"flicker_moving", finite(r.pathFlicker)},
            {"error_settled", finite(r.convergedError)},
            {"error_elsewhere", finite(r.restError)},
            {"error_settled_fresh", finite(r.freshSettledError)},
            {"ghost_left", finite(r.ghostLeft)},
            {"tolerance", finite(r.tolerance)},
            {"recovery_frames", r.recoveryFrames},
            {"excess_over_fresh", finite(r.excessOverFresh)},
            {"excess_over_unresized", finite(r.excessOverUnresized)},
            {"stale_after", finite(r.staleAfter)},
            {"reused_at_change", finite(r.reusedAtChange)},
            {"kept_unseen", finite(r.keptUnseen)},
            {"geometry_pixels", r.geometryPixels},
            {"truth_start", finite(r.truthStart)},
            {"truth_fresh", finite(r.truthFresh)},
            {"truth_tested", finite(r.truthEnd)},
            {"truth_elsewhere", finite(r.truthRest)},
            {"frames", frames}};
}

int run(int argc, char** argv) {
    const Args args = parseArgs(argc, argv);
    const fs::path out(args.out);
    // No output over an input (a case's scene file) or over another output, before any work.
    std::vector<RunFile> inputs, outputs;
    for (const Case& c : args.cases) {
        inputs.push_back({"the scene file of case " + c.name, args.run.repository + "/" + c.scene});
        outputs.push_back({"the picture of case " + c.name,
                           (out / "images" / ("stability-" + c.name + ".png")).string()});
    }
    for (const char* name : {"stability.md", "stability.csv", "frames.csv", "stability.json"})
        outputs.push_back({"--out's " + std::string(name), (out / name).string()});
    checkRunFiles(inputs, outputs);
    vk::Context ctx({args.common.validation, args.common.device});
    fs::create_directories(out / "images");
    std::vector<CaseResult> results;
    std::ostringstream csv, perFrame;
    csv << "case,region,region_pixels,non_finite,flicker_still,flicker_moving,error_settled,"
           "error_elsewhere,tolerance,recovery_frames,excess_over_fresh,stale_after,truth_start,"
           "truth_fresh,truth_tested,truth_elsewhere,seconds\n";
    perFrame << "case,frame,phase,since_change,flicker,error,error_rest,fresh_error,stale,"
                "ao_reused,non_finite\n";
    nlohmann::json json = {{"device", ctx.properties.deviceName}, {"settings", args.run.settings},
                           {"warmup", args.run.warmup},           {"hold", args.run.hold},
                           {"converge", args.run.converge},       {"truth_spp", args.run.truthSpp}};
    for (const Case& c : args.cases) {
        const auto begin = std::chrono::steady_clock::now();
        CaseResult r = runCase(ctx, c, args.run, [](const std::string& line) {
            std::fprintf(stderr, "%s\n", line.c_str());
        });
        const double seconds =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - begin).count();
        const std::string unresized =
            std::isfinite(r.excessOverUnresized)
                ? "  over the unresized " + number(r.excessOverUnresized + 1.0, 3) + "x"
                : "";
        std::printf("%-13s region %6zu px  NaN/Inf %zu  flicker %.4f  recovery %d  excess %s%s  "
                    "(%.0f s)\n",
                    c.name.c_str(), r.regionPixels, r.nonFinite, r.stillFlicker, r.recoveryFrames,
                    number(r.excessOverFresh, 2).c_str(), unresized.c_str(), seconds);
        csv << c.name << "," << regionName(c.region) << "," << r.regionPixels << "," << r.nonFinite
            << "," << r.stillFlicker << "," << r.pathFlicker << "," << r.convergedError << ","
            << r.restError << "," << r.tolerance << "," << r.recoveryFrames << ","
            << r.excessOverFresh << "," << r.staleAfter << "," << r.truthStart << ","
            << r.truthFresh << "," << r.truthEnd << "," << r.truthRest << "," << seconds << "\n";
        for (size_t i = 0; i < r.frames.size(); ++i) {
            const FrameRecord& f = r.frames[i];
            perFrame << c.name << "," << i << "," << f.phase << "," << f.sinceChange << ","
                     << f.flicker << "," << f.error << "," << f.errorRest << "," << f.freshError
                     << "," << f.stale << "," << f.reused << "," << f.nonFinite << "\n";
        }
        json["cases"].push_back(toJson(r));
        json["cases"].back()["seconds"] = seconds;
        writeStrip((out / "images" / ("stability-" + c.name + ".png")).string(), r);
        results.push_back(std::move(r));
    }
    const std::string md = table(results);
    cli::writeTextAtomically((out / "stability.md").string(), md);
    cli::writeTextAtomically((out / "stability.csv").string(), csv.str());
    cli::writeTextAtomically((out / "frames.csv").string(), perFrame.str());
    cli::writeTextAtomically((out / "stability.json").string(), json.dump(1) + "\n");
    std::printf("\n%s\nwrote %s/stability.{md,csv,json}, frames.csv, images/\n", md.c_str(),
                args.out.c_str());
    if (args.plot) {
        // python3 first; Debian's own where python3 on the PATH is another one (pyenv, venv)
        // without python3-matplotlib.
        const std::string script = cli::dataDirectory() + "/docs/stability_plot.py";
        bool plotted = false;
        for (const char* python : {"python3", "/usr/bin/python3"}) {
            const std::string command =
                std::string(python) + " '" + script + "' '" + args.out + "' 2>/dev/null";
            if ((plotted = std::system(command.c_str()) == 0)) break;
        }
        if (!plotted)
            std::fprintf(stderr, "note: no plots (docs/stability_plot.py needs python3 with "
                                 "matplotlib: apt-get install python3-matplotlib)\n");
    }
    size_t nonFinite = 0;
    for (const CaseResult& r : results)
        nonFinite += r.nonFinite;
    if (nonFinite > 0) {
        std::fprintf(stderr, "error: %zu NaN/Inf values in the images (see the table)\n",
                     nonFinite);
        return 1;
    }
    return cli::validationStatus(ctx.validationMessageCount());
}

} // namespace

int main(int argc, char** argv) {
    return cli::guardedMain(argc, argv, run);
}
