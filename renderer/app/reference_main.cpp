// reference: renders the path-traced ground truth of a scene in one of the modes that match
// the real-time effects, progressively, and writes it as linear EXR (cached by content).
#include "app/cli.h"
#include "image_io.h"
#include "metrics/comparison.h"
#include "metrics/golden.h"
#include "reference/cache.h"
#include "scene/animation.h"
#include "scene/camera.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <limits>

namespace fs = std::filesystem;
using namespace ssgi;
using namespace ssgi::reference;

namespace {

const char* kUsage = R"(usage: reference [SCENE] [options]
  SCENE                 scene file (.json) or glTF (.gltf/.glb), or a shipped scene's name
                        (cornell-box, sponza, ...; an unknown name lists them); default
                        cornell-box
  --mode M              direct, ao, indirect, full, multi or sky (default full)
  --size WxH            image size (default 256x256)
  --noise T             stop once the estimated noise (relative error against the converged
                        image) is at most T (default 0.01, after 16 samples); 0: no target
  --spp N               samples per pixel, at most (default 65536)
  --seed S              random seed (default 1); same seed and options, same image
  --threads N           worker threads (default: every hardware thread); the image is the same
  --time T              time in seconds along the scene's camera path and object paths
  --jitter              random sub-pixel positions (full and multi only); without it every
                        sample goes through the pixel centre, as the real-time G-buffer's does
  --light-radius R      replace the light's disk radius (0: a point light, hard shadows)
  --output FILE.exr     linear image (default out/<scene>-<mode>-ref.exr)
  --png FILE.png        also a display image: the composite's exposure, tonemap and sRGB
                        (AO is written as it is)
  --cache DIR           reference cache (default $SSGI_REFERENCE_CACHE, else build/reference-cache)
  --no-cache            render even when the cache holds the image, and store nothing
  --quiet               no progress bar
)";

struct Args {
    std::string scene, output, png, cacheDir = defaultCacheDir();
    ReferenceOptions options;
    float time = -1.0f, lightRadius = -1.0f;
    bool useCache = true;
};

uint64_t parseWhole(const std::string& option, const std::string& text, uint64_t lo, uint64_t hi) {
    char* end = nullptr;
    const unsigned long long v = std::strtoull(text.c_str(), &end, 10);
    if (text.empty() || text[0] == '-' || *end != '\0' || v < lo || v > hi)
        throw InputError(option + ": '" + text + "' is not a whole number in " +
                         std::to_string(lo) + ".." + std::to_string(hi));
    return v;
}

double parseNumber(const std::string& option, const std::string& text, double lo, double hi) {
    char* end = nullptr;
    const double v = std::strtod(text.c_str(), &end);
    if (text.empty() || *end != '\0' || !(v >= lo && v <= hi))
        throw InputError(option + ": '" + text + "' is not a number in [" + std::to_string(lo) +
                         ", " + std::to_string(hi) + "]");
    return v;
}

Args parseArgs(int argc, char** argv) {
    Args a;
    a.options.width = a.options.height = 256;
    a.options.spp = kDefaultSampleCap;
    a.options.noiseTarget = kDefaultNoiseTarget;
    a.options.progress = true;
    auto value = [&](int& i) -> std::string {
        if (i + 1 >= argc) throw InputError(std::string(argv[i]) + " needs a value");
        return argv[++i];
    };
    for (int i = 1; i < argc; ++i) {
        const std::string arg = argv[i];
        if (arg == "--help" || arg == "-h") {
            std::cout << kUsage;
            std::exit(0);
        } else if (arg == "--mode") {
            a.options.mode = parseMode(value(i));
        } else if (arg == "--size") {
            const std::string v = value(i);
            const size_t x = v.find('x');
            if (x == std::string::npos) throw InputError("--size: expected WxH, got '" + v + "'");
            a.options.width = uint32_t(parseWhole("--size", v.substr(0, x), 1, kMaxImageSide));
            a.options.height = uint32_t(parseWhole("--size", v.substr(x + 1), 1, kMaxImageSide));
        } else if (arg == "--spp") {
            a.options.spp = uint32_t(parseWhole(arg, value(i), 1, 1u << 24));
        } else if (arg == "--noise") {
            // A target too small to reach is refused by renderReference, for the module too.
            a.options.noiseTarget = parseNumber(arg, value(i), 0.0, 1.0);
        } else if (arg == "--seed") {
            a.options.seed = parseWhole(arg, value(i), 0, UINT64_MAX);
        } else if (arg == "--threads") {
            a.options.threads = unsigned(parseWhole(arg, value(i), 1, 1024));
        } else if (arg == "--time") {
            a.time = float(parseNumber(arg, value(i), 0.0, 1e9));
        } else if (arg == "--jitter") {
            a.options.jitter = true;
        } else if (arg == "--light-radius") {
            a.lightRadius = float(parseNumber(arg, value(i), 0.0, 1e9));
        } else if (arg == "--output") {
            a.output = value(i);
        } else if (arg == "--png") {
            a.png = value(i);
        } else if (arg == "--cache") {
            a.cacheDir = value(i);
        } else if (arg == "--no-cache") {
            a.useCache = false;
        } else if (arg == "--quiet") {
            a.options.progress = false;
        } else if (arg.rfind("--", 0) == 0) {
            throw InputError("unknown option " + arg + " (see reference --help)");
        } else if (a.scene.empty()) {
            a.scene = arg;
        } else {
            throw InputError("more than one scene given: " + a.scene + " and " + arg);
        }
    }
    a.scene = cli::resolveScene(a.scene);
    if (a.output.empty())
        a.output = "out/" + fs::path(a.scene).stem().string() + "-" + modeName(a.options.mode) +
                   "-ref.exr";
    if (fs::path(a.output).extension() != ".exr")
        throw InputError("--output: '" + a.output + "' must end in .exr");
    if (!a.png.empty() && fs::path(a.png).extension() != ".png")
        throw InputError("--png: '" + a.png + "' must end in .png");
    return a;
}

int run(int argc, char** argv) {
    const Args args = parseArgs(argc, argv);
    Scene scene = loadScene(args.scene);
    // No output over an input or over another output, before any work.
    std::vector<RunFile> outputs = {{"--output", args.output}};
    if (!args.png.empty()) outputs.push_back({"--png", args.png});
    checkRunFiles(cli::sceneInputs(scene), outputs);
    const float exposure = float(scene.settings.exposure); // of the display image (--png)
    ReferenceRequest request;
    request.options = args.options;
    request.time = args.time;
    request.lightRadius = args.lightRadius;
    request.useCache = args.useCache;
    request.cacheDir = args.cacheDir;
    const auto start = std::chrono::steady_clock::now();
    bool fromCache = false;
    const ReferenceImage image =
        requestedReference(std::move(scene), args.scene, request, &fromCache);
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

    // The EXR's header records the samples and the noise, which compare prints beside its figures.
    std::vector<ImageFile> files = {
        {args.output, image.width, image.height, &image.rgba,
         metrics::noiseAttributes({image.samples, image.noise}, modeName(args.options.mode))}};
    std::vector<float> shown;
    if (!args.png.empty()) {
        shown = image.rgba;
        for (size_t i = 0; i < shown.size(); ++i) {
            if (i % 4 == 3)
                shown[i] = 1.0f;
            else if (args.options.mode != Mode::Ao)
                shown[i] = metrics::displayValue(shown[i], exposure);
        }
        files.push_back({args.png, image.width, image.height, &shown});
    }
    writeImages(files); // both or neither
    char noise[32] = "not estimated";
    if (std::isfinite(image.noise))
        std::snprintf(noise, sizeof noise, "%.2f%%", 100.0 * image.noise);
    std::printf("wrote %s%s%s (%ux%u, mode %s, %u spp, noise %s, %s in %.1f s)\n",
                args.output.c_str(), args.png.empty() ? "" : " and ", args.png.c_str(), image.width,
                image.height, modeName(args.options.mode), image.samples, noise,
                fromCache ? "from the cache" : "rendered", seconds);
    if (image.nonFiniteSamples > 0) {
        std::fprintf(stderr, "error: %llu samples were NaN or infinite and were dropped\n",
                     (unsigned long long)image.nonFiniteSamples);
        return 1;
    }
    return 0;
}

} // namespace

int main(int argc, char** argv) {
    return ssgi::cli::guardedMain(argc, argv, run);
}
