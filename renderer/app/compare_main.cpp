// compare: error figures of an image against a reference (relMSE, RMSE, mean absolute error,
// SSIM) over the whole image, inside masks and inside a screen-edge band; a table on stdout,
// every figure as JSON, and a false-colour error map.
#include "app/cli.h"
#include "image_io.h"
#include "metrics/error_map.h"
#include "scene/scene.h"

#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <unistd.h>

namespace fs = std::filesystem;
using namespace ssgi;
using namespace ssgi::metrics;

namespace {

const char* kUsage = R"(usage: compare A B [options]
  A                     the image to judge (e.g. the real-time render), .exr or .png
  B                     the reference it is measured against (relMSE divides by B)
  --mask M.png          also measure inside the pixels where M is above 0.5 (repeatable)
  --edge-band K         also measure inside the K pixels along the image border
  --json FILE           write every figure as JSON
  --error-map FILE.png  write a false-colour map of per-pixel relative error (log scale,
                        black 0.1% .. pale yellow 100%; cyan where A is NaN or infinite)
)";

struct Args {
    std::string test, reference, json, errorMap;
    std::vector<std::string> masks;
    uint32_t edgeBand = 0;
};

Args parseArgs(int argc, char** argv) {
    Args a;
    std::vector<std::string> images;
    auto value = [&](int& i) -> std::string {
        if (i + 1 >= argc) throw InputError(std::string(argv[i]) + " needs a value");
        return argv[++i];
    };
    for (int i = 1; i < argc; ++i) {
        const std::string arg = argv[i];
        if (arg == "--help" || arg == "-h") {
            std::cout << kUsage;
            std::exit(0);
        } else if (arg == "--mask") {
            a.masks.push_back(value(i));
        } else if (arg == "--edge-band") {
            const std::string v = value(i);
            char* end = nullptr;
            const long k = std::strtol(v.c_str(), &end, 10);
            if (v.empty() || *end != '\0' || k < 1 || k > 100000)
                throw InputError("--edge-band: '" + v + "' is not a whole number of pixels >= 1");
            a.edgeBand = uint32_t(k);
        } else if (arg == "--json") {
            a.json = value(i);
        } else if (arg == "--error-map") {
            a.errorMap = value(i);
            if (fs::path(a.errorMap).extension() != ".png")
                throw InputError("--error-map: '" + a.errorMap + "' must end in .png");
        } else if (arg.rfind("--", 0) == 0) {
            throw InputError("unknown option " + arg + " (see compare --help)");
        } else {
            images.push_back(arg);
        }
    }
    if (images.size() != 2)
        throw InputError("expected two images, the one to judge and the reference, got " +
                         std::to_string(images.size()) + " (see compare --help)");
    a.test = images[0];
    a.reference = images[1];
    return a;
}

Image load(const std::string& path) {
    if (!fs::exists(path)) throw InputError(path + ": no such file");
    Image image;
    image.rgba = readImage(path, image.width, image.height);
    return image;
}

void requireSize(const Image& image, const std::string& path, const Image& like,
                 const std::string& likePath) {
    if (image.width != like.width || image.height != like.height)
        throw InputError(path + ": " + std::to_string(image.width) + "x" +
                         std::to_string(image.height) + " differs from " + likePath + " (" +
                         std::to_string(like.width) + "x" + std::to_string(like.height) + ")");
}

nlohmann::json number(double v) {
    return std::isfinite(v) ? nlohmann::json(v) : nullptr;
}

int run(int argc, char** argv) {
    const Args args = parseArgs(argc, argv);
    const Image test = load(args.test), reference = load(args.reference);
    requireSize(reference, args.reference, test, args.test);

    std::vector<std::pair<std::string, Mask>> regions = {{"image", Mask()}};
    if (args.edgeBand > 0)
        regions.emplace_back("edge band " + std::to_string(args.edgeBand) + " px",
                             edgeBandMask(test.width, test.height, args.edgeBand));
    for (const std::string& path : args.masks) {
        const Image mask = load(path);
        requireSize(mask, path, test, args.test);
        regions.emplace_back("mask " + path, thresholdMask(mask));
    }

    size_t nonFinite = 0;
    for (size_t i = 0; i < test.pixels(); ++i)
        nonFinite += !std::isfinite(test.rgba[4 * i] + test.rgba[4 * i + 1] + test.rgba[4 * i + 2]);

    const std::vector<double> ssim = ssimMap(test, reference);
    nlohmann::json jsonRegions = nlohmann::json::array();
    std::printf("%s against %s (%ux%u)\n", args.test.c_str(), args.reference.c_str(), test.width,
                test.height);
    std::printf("%-28s %8s %11s %11s %11s %8s\n", "region", "pixels", "relMSE", "RMSE", "MAE",
                "SSIM");
    for (const auto& [name, mask] : regions) {
        const Figures f = errorFigures(test, reference, mask, ssim);
        std::printf("%-28s %8zu %11.4e %11.4e %11.4e %8.4f\n", name.c_str(), f.pixels, f.relMse,
                    f.rmse, f.mae, f.ssim);
        jsonRegions.push_back({{"name", name},
                               {"pixels", f.pixels},
                               {"relmse", number(f.relMse)},
                               {"rmse", number(f.rmse)},
                               {"mae", number(f.mae)},
                               {"ssim", number(f.ssim)}});
    }
    if (nonFinite > 0)
        std::printf("%zu pixels of %s are NaN or infinite\n", nonFinite, args.test.c_str());

    if (!args.errorMap.empty()) {
        writeImage(args.errorMap, test.width, test.height, errorMap(test, reference));
        std::printf("wrote %s\n", args.errorMap.c_str());
    }
    if (!args.json.empty()) {
        const nlohmann::json j = {{"test", args.test},
                                  {"reference", args.reference},
                                  {"width", test.width},
                                  {"height", test.height},
                                  {"non_finite_pixels", nonFinite},
                                  {"regions", jsonRegions},
                                  {"error_map", args.errorMap.empty()
                                                    ? nlohmann::json(nullptr)
                                                    : nlohmann::json(args.errorMap)}};
        cli::writeTextAtomically(args.json, j.dump(2) + "\n");
    }
    return 0;
}

} // namespace

int main(int argc, char** argv) {
    return ssgi::cli::guardedMain(argc, argv, run);
}
