#include "metrics/comparison.h"

#include "image_io.h"
#include "metrics/golden.h"
#include "scene/scene.h"
#include "scene/warnings.h"

#include <cmath>
#include <cstdio>

namespace ssgi::metrics {

Image loadImage(const std::string& path, ImageAttributes* attributes) {
    Image image;
    image.rgba = readImage(path, image.width, image.height, attributes);
    return image;
}

namespace {
const char* const kSamplesAttribute = "ssgi:samples";
const char* const kNoiseAttribute = "ssgi:noise";
const char* const kModeAttribute = "ssgi:mode";
} // namespace

ImageAttributes noiseAttributes(const RecordedNoise& noise, const std::string& mode) {
    ImageAttributes a;
    a.ints[kSamplesAttribute] = int(noise.samples);
    if (noise.estimated()) a.floats[kNoiseAttribute] = float(noise.noise);
    a.texts[kModeAttribute] = mode;
    return a;
}

RecordedNoise recordedNoise(const ImageAttributes& attributes) {
    RecordedNoise r;
    const auto samples = attributes.ints.find(kSamplesAttribute);
    if (samples == attributes.ints.end() || samples->second < 1) return r;
    r.samples = uint32_t(samples->second);
    const auto noise = attributes.floats.find(kNoiseAttribute);
    if (noise != attributes.floats.end() && std::isfinite(noise->second) && noise->second >= 0.0f)
        r.noise = noise->second;
    return r;
}

void warnIfNotOpaque(const Image& image, const std::string& name) {
    // The figures read the colour as stored; a transparent pixel's colour is not weighed by it.
    size_t transparent = 0;
    for (size_t i = 0; i < image.pixels(); ++i)
        transparent += image.rgba[4 * i + 3] < 1.0f;
    if (transparent > 0)
        warn(name + ": " + std::to_string(transparent) +
             " pixels are not opaque; their colour is compared as stored, alpha is not applied");
}

size_t nonFinitePixels(const Image& image) {
    size_t count = 0;
    for (size_t i = 0; i < image.pixels(); ++i)
        count += !std::isfinite(image.rgba[4 * i] + image.rgba[4 * i + 1] + image.rgba[4 * i + 2]);
    return count;
}

void requireSize(const Image& image, const std::string& name, const Image& like,
                 const std::string& likeName) {
    if (image.width != like.width || image.height != like.height)
        throw InputError(name + ": " + std::to_string(image.width) + "x" +
                         std::to_string(image.height) + " differs from " + likeName + " (" +
                         std::to_string(like.width) + "x" + std::to_string(like.height) + ")");
}

void requireComparable(const std::string& testName, bool testLinear,
                       const std::string& referenceName, bool referenceLinear,
                       const Image& reference) {
    const auto kind = [](bool linear) { return linear ? "linear" : "tonemapped sRGB"; };
    if (testLinear != referenceLinear)
        throw InputError(testName + " (" + kind(testLinear) + ") and " + referenceName + " (" +
                         kind(referenceLinear) +
                         ") hold different quantities: compare a .png with a .png, an .exr with "
                         "an .exr");
    if (const size_t bad = nonFinitePixels(reference))
        throw InputError(referenceName + ": " + std::to_string(bad) +
                         " pixels are NaN or infinite; a reference must be finite");
}

Comparison compareImages(const Image& test, const Image& reference,
                         const ComparisonOptions& options) {
    requireSize(reference, "reference", test, "test");
    Comparison c;
    c.nonFinitePixels = nonFinitePixels(test);
    c.ssim = ssimMap(test, reference);
    c.regions.emplace_back("image", errorFigures(test, reference, Mask(), c.ssim));
    for (const auto& [name, mask] : options.regions)
        c.regions.emplace_back(name, errorFigures(test, reference, mask, c.ssim));
    // FLIP and the golden-image count judge what a user sees, so both read the display images.
    const Image testDisplay = displayImage(test, options.linear, options.exposure);
    const Image referenceDisplay = displayImage(reference, options.linear, options.exposure);
    c.flip = flip::flip(testDisplay, referenceDisplay, options.ppd);
    if (options.maxDiff >= 0.0)
        c.diffFraction = fractionDiffering(testDisplay, referenceDisplay, options.maxDiff);
    return c;
}

} // namespace ssgi::metrics
