// compare: error figures of an image against a reference (relMSE, RMSE, mean absolute error,
// SSIM) over the whole image, inside masks and inside a screen-edge band, and LDR-FLIP of the
// display images; a table on stdout, every figure as JSON, false-colour maps, and thresholds
// that set the exit status so that CI can fail a render against a stored golden image.
#include "app/cli.h"
#include "image_io.h"
#include "metrics/comparison.h"
#include "metrics/error_map.h"
#include "scene/scene.h"

#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <limits>
#include <unistd.h>

namespace fs = std::filesystem;
using namespace ssgi;
using namespace ssgi::metrics;

namespace {

const char* kUsage = R"(usage: compare A B [options]
  A                     the image to judge (e.g. the real-time render), .exr or .png
  B                     the reference it is measured against (relMSE divides by B); an .exr
                        written by reference records its own noise, printed beside the relMSE
  --mask M.png          also measure inside the pixels where M is above 0.5 (repeatable)
  --edge-band K         also measure inside the K pixels along the image border
  --json FILE           write every figure as JSON
  --error-map FILE.png  write a false-colour map of per-pixel relative error (log scale,
                        black 0.1% .. pale yellow 100%; cyan where A is NaN or infinite)
  --flip-map FILE.png   write the per-pixel FLIP of the display images (same colours, linear:
                        black 0 .. pale yellow 1; cyan where it is NaN)
  --ppd P               FLIP's pixels per degree of visual angle (default 67: a 0.7 m wide
                        3840-pixel monitor seen from 0.7 m, as in the FLIP paper)
  --exposure E          exposure of a linear .exr's display image (default 1; give the scene's)

Display images (what --max-diff, FLIP and --flip-map look at): a .png as stored, its 8-bit
sRGB-encoded values; a .exr holds linear radiance and is tonemapped as the composite pass does
it (times --exposure, ACES fit, sRGB encoding), then rounded to 8 bits. relMSE, RMSE, MAE and
SSIM use the values as read (linear for .exr). FLIP is LDR-FLIP (Andersson et al. 2020).

The reference's own noise: relMSE against a noisy reference is the image's error plus the
reference's noise^2 (plus A's, where A is a reference too). The column "noise" is that part, as
the EXRs' headers record it; a relMSE within 10x of it gets a warning (it measures the references
as much as the image), and a reference that records no noise is said to.

Thresholds: each one exceeded prints a FAIL line and makes the exit status 1; 0 when all pass
(2 for bad input). NaN never passes.
  --max-relmse X        relMSE over the whole image (masks and the edge band are reported only)
  --max-diff D          golden-image test on the display images: a pixel differs when any of
                        R, G, B differs by more than D in 0-255 units of the 8-bit display
                        image (a .png's stored values; a .exr's tonemapped ones)
  --max-fraction F      at most this fraction (0..1) of the pixels may differ (default 0;
                        needs --max-diff); e.g. --max-diff 5 --max-fraction 0.001
  --max-flip X          mean FLIP (0..1)
)";

struct Args {
    std::string test, reference, json, errorMap, flipMap;
    std::vector<std::string> masks;
    uint32_t edgeBand = 0;
    double ppd = metrics::flip::kDefaultPpd, exposure = 1.0;
    // Thresholds; negative = not given.
    double maxRelMse = -1.0, maxDiff = -1.0, maxFraction = -1.0, maxFlip = -1.0;
};

constexpr double kInf = std::numeric_limits<double>::infinity();

// FAIL or PASS lines on stdout: a threshold exceeded is a result of the comparison, not an error
// of the command; the exit status carries it.
struct Check {
    std::string name;
    double value, limit;
    bool pass() const { return value <= limit; } // false for NaN
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
        } else if (arg == "--flip-map") {
            a.flipMap = value(i);
            if (fs::path(a.flipMap).extension() != ".png")
                throw InputError("--flip-map: '" + a.flipMap + "' must end in .png");
        } else if (arg == "--ppd") {
            a.ppd = cli::parseNumber(arg, value(i), 1e-3, 1e4);
        } else if (arg == "--exposure") {
            a.exposure = cli::parseNumber(arg, value(i), 1e-6, 1e6);
        } else if (arg == "--max-relmse") {
            a.maxRelMse = cli::parseNumber(arg, value(i), 0.0, kInf);
        } else if (arg == "--max-diff") {
            a.maxDiff = cli::parseNumber(arg, value(i), 0.0, 255.0);
        } else if (arg == "--max-fraction") {
            a.maxFraction = cli::parseNumber(arg, value(i), 0.0, 1.0);
        } else if (arg == "--max-flip") {
            a.maxFlip = cli::parseNumber(arg, value(i), 0.0, 1.0);
        } else if (arg.rfind("--", 0) == 0) {
            throw InputError("unknown option " + arg + " (see compare --help)");
        } else {
            images.push_back(arg);
        }
    }
    if (a.maxFraction >= 0.0 && a.maxDiff < 0.0)
        throw InputError("--max-fraction needs --max-diff (the difference that counts)");
    if (a.maxDiff >= 0.0 && a.maxFraction < 0.0) a.maxFraction = 0.0;
    if (images.size() != 2)
        throw InputError("expected two images, the one to judge and the reference, got " +
                         std::to_string(images.size()) + " (see compare --help)");
    a.test = images[0];
    a.reference = images[1];
    return a;
}

// An image file; a warning on stderr when it has pixels that are not opaque.
Image load(const std::string& path, ImageAttributes* attributes = nullptr) {
    Image image = loadImage(path, attributes);
    warnIfNotOpaque(image, path);
    return image;
}

nlohmann::json number(double v) {
    return std::isfinite(v) ? nlohmann::json(v) : nullptr;
}

nlohmann::json noiseJson(const RecordedNoise& r) {
    if (!r.recorded()) return nullptr;
    return {{"samples", r.samples}, {"noise", number(r.noise)}};
}

// What a file records of its own noise, as one line: "a reference of 20964 spp, noise 1.00%".
std::string describe(const RecordedNoise& r) {
    char text[96];
    if (r.estimated())
        std::snprintf(text, sizeof text, "a reference of %u spp, noise %.2f%% (relMSE %.1e)",
                      r.samples, 100.0 * r.noise, r.noise * r.noise);
    else
        std::snprintf(text, sizeof text, "a reference of %u spp, its noise not estimated",
                      r.samples);
    return text;
}

bool isLinear(const std::string& path) {
    return fs::path(path).extension() == ".exr";
}

int run(int argc, char** argv) {
    const Args args = parseArgs(argc, argv);
    // No output over an input or over another output, before any work.
    std::vector<RunFile> inputs = {{"the image to judge", args.test},
                                   {"the reference image", args.reference}};
    for (const std::string& mask : args.masks)
        inputs.push_back({"--mask", mask});
    std::vector<RunFile> outputs;
    if (!args.json.empty()) outputs.push_back({"--json", args.json});
    if (!args.errorMap.empty()) outputs.push_back({"--error-map", args.errorMap});
    if (!args.flipMap.empty()) outputs.push_back({"--flip-map", args.flipMap});
    checkRunFiles(inputs, outputs);
    ImageAttributes testHeader, referenceHeader;
    const Image test = load(args.test, &testHeader),
                reference = load(args.reference, &referenceHeader);
    const RecordedNoise testNoise = recordedNoise(testHeader),
                        referenceNoise = recordedNoise(referenceHeader);
    requireSize(reference, args.reference, test, args.test);
    requireComparable(args.test, isLinear(args.test), args.reference, isLinear(args.reference),
                      reference);

    ComparisonOptions options;
    options.linear = isLinear(args.test);
    options.exposure = args.exposure;
    options.ppd = args.ppd;
    options.maxDiff = args.maxDiff;
    if (args.edgeBand > 0)
        options.regions.emplace_back("edge band " + std::to_string(args.edgeBand) + " px",
                                     edgeBandMask(test.width, test.height, args.edgeBand));
    for (const std::string& path : args.masks) {
        const Image mask = load(path);
        requireSize(mask, path, test, args.test);
        options.regions.emplace_back("mask " + path, thresholdMask(mask));
    }
    const Comparison comparison = compareImages(test, reference, options);

    std::vector<Check> checks;
    nlohmann::json jsonRegions = nlohmann::json::array();
    std::printf("%s against %s (%ux%u)\n", args.test.c_str(), args.reference.c_str(), test.width,
                test.height);
    // The part of each relMSE that is the references' own noise: B's, and A's where A is a
    // reference too (two seeds of one reference differ by the sum).
    double noiseFloor = std::numeric_limits<double>::quiet_NaN();
    if (referenceNoise.recorded()) {
        std::printf("%s: %s\n", args.reference.c_str(), describe(referenceNoise).c_str());
        noiseFloor = referenceNoise.noise * referenceNoise.noise;
    } else {
        std::printf("%s records no noise of its own (not an EXR written by reference): every "
                    "figure below holds the reference's noise, of unknown size\n",
                    args.reference.c_str());
    }
    if (testNoise.recorded()) {
        std::printf("%s: %s\n", args.test.c_str(), describe(testNoise).c_str());
        noiseFloor += testNoise.noise * testNoise.noise;
    }
    std::printf("%-28s %8s %11s %9s %11s %11s %8s\n", "region", "pixels", "relMSE", "noise", "RMSE",
                "MAE", "SSIM");
    std::vector<std::string> nearNoise;
    for (const auto& [name, f] : comparison.regions) {
        if (name == "image" && args.maxRelMse >= 0.0)
            checks.push_back({"relMSE", f.relMse, args.maxRelMse});
        char floor[16] = "?";
        if (std::isfinite(noiseFloor)) std::snprintf(floor, sizeof floor, "%.1e", noiseFloor);
        std::printf("%-28s %8zu %11.4e %9s %11.4e %11.4e %8.4f\n", name.c_str(), f.pixels, f.relMse,
                    floor, f.rmse, f.mae, f.ssim);
        const bool near = f.relMse < kNoiseMargin * noiseFloor; // false for NaN
        if (near) {
            char line[256];
            std::snprintf(line, sizeof line,
                          "warning: %s: relMSE %.2e is within %gx of the references' own noise "
                          "(%.1e): it measures the reference as much as the image; render the "
                          "reference to a lower --noise",
                          name.c_str(), f.relMse, kNoiseMargin, noiseFloor);
            nearNoise.push_back(line);
        }
        jsonRegions.push_back({{"name", name},
                               {"pixels", f.pixels},
                               {"relmse", number(f.relMse)},
                               {"relmse_noise", number(noiseFloor)},
                               {"within_noise_margin", near},
                               {"rmse", number(f.rmse)},
                               {"mae", number(f.mae)},
                               {"ssim", number(f.ssim)}});
    }
    for (const std::string& line : nearNoise)
        std::fprintf(stderr, "%s\n", line.c_str());
    const size_t nonFinite = comparison.nonFinitePixels;
    if (nonFinite > 0)
        std::printf("%zu pixels of %s are NaN or infinite\n", nonFinite, args.test.c_str());

    const flip::Result& flipResult = comparison.flip;
    std::printf("mean FLIP %.4f (display images, %g pixels per degree)\n", flipResult.mean,
                args.ppd);
    if (args.maxFlip >= 0.0) checks.push_back({"mean FLIP", flipResult.mean, args.maxFlip});
    const double fraction = comparison.diffFraction;
    if (args.maxDiff >= 0.0) {
        std::printf("%.4g of the pixels differ by more than %g/255 in a channel\n", fraction,
                    args.maxDiff);
        char name[64];
        std::snprintf(name, sizeof name, "fraction of pixels off by more than %g/255",
                      args.maxDiff);
        checks.push_back({name, fraction, args.maxFraction});
    }

    if (!args.flipMap.empty()) {
        writeImage(args.flipMap, test.width, test.height, flip::flipErrorMap(flipResult.map));
        std::printf("wrote %s\n", args.flipMap.c_str());
    }
    if (!args.errorMap.empty()) {
        writeImage(args.errorMap, test.width, test.height, errorMap(test, reference));
        std::printf("wrote %s\n", args.errorMap.c_str());
    }
    size_t failed = 0;
    nlohmann::json jsonChecks = nlohmann::json::array();
    for (const Check& c : checks) {
        std::printf("%s: %s %.4g %s %g\n", c.pass() ? "PASS" : "FAIL", c.name.c_str(), c.value,
                    c.pass() ? "<=" : ">", c.limit);
        failed += !c.pass();
        jsonChecks.push_back(
            {{"name", c.name}, {"value", number(c.value)}, {"limit", c.limit}, {"pass", c.pass()}});
    }
    if (!args.json.empty()) {
        const nlohmann::json j = {{"test", args.test},
                                  {"reference", args.reference},
                                  {"width", test.width},
                                  {"height", test.height},
                                  {"non_finite_pixels", nonFinite},
                                  {"reference_noise", noiseJson(referenceNoise)},
                                  {"test_noise", noiseJson(testNoise)},
                                  {"regions", jsonRegions},
                                  {"flip", number(flipResult.mean)},
                                  {"ppd", args.ppd},
                                  {"flip_map", args.flipMap.empty() ? nlohmann::json(nullptr)
                                                                    : nlohmann::json(args.flipMap)},
                                  {"diff_fraction", number(fraction)},
                                  {"checks", jsonChecks},
                                  {"pass", failed == 0},
                                  {"error_map", args.errorMap.empty()
                                                    ? nlohmann::json(nullptr)
                                                    : nlohmann::json(args.errorMap)}};
        cli::writeTextAtomically(args.json, j.dump(2) + "\n");
    }
    return failed == 0 ? 0 : 1;
}

} // namespace

int main(int argc, char** argv) {
    return ssgi::cli::guardedMain(argc, argv, run);
}
