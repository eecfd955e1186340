// One comparison of an image against a reference, as `compare` makes it and the Python module
// returns it: the figures over the whole image and inside regions, the SSIM and FLIP maps, and
// the golden-image count of visibly differing pixels. The checks that make two images comparable
// (same size, the same kind of values, a finite reference) are here too, with their messages.
#pragma once

#include "image_io.h"
#include "metrics/flip.h"
#include "metrics/metrics.h"

#include <limits>
#include <string>
#include <utility>
#include <vector>

namespace ssgi::metrics {

// An image file as RGBA floats, as readImage reads it (the colour as stored, grey as R = G = B);
// InputError naming the file when it is missing, unreadable, not a regular file or too large.
// `attributes`, when given, gets its header's attributes.
Image loadImage(const std::string& path, ImageAttributes* attributes = nullptr);

// A path-traced reference's own noise, as `reference` records it in its EXR's header: its samples
// per pixel and its estimated noise, the expected relative error against the converged image, so
// that noise^2 is about the relMSE the reference alone adds to every comparison against it.
struct RecordedNoise {
    uint32_t samples = 0; // 0: the file records nothing (it was not written by `reference`)
    double noise = std::numeric_limits<double>::quiet_NaN(); // NaN: too few samples to estimate
    bool recorded() const { return samples > 0; }
    bool estimated() const { return recorded() && noise >= 0.0; }
};
// The header attributes that record it (ssgi:samples, ssgi:noise; ssgi:mode names the mode).
ImageAttributes noiseAttributes(const RecordedNoise& noise, const std::string& mode);
// What a file's header records; nothing when it lacks ssgi:samples or holds impossible values.
RecordedNoise recordedNoise(const ImageAttributes& attributes);
// A figure is no better than this many times the noise it carries: compare warns below it.
constexpr double kNoiseMargin = 10.0;

// A warning on stderr naming `name` when pixels of `image` are not opaque: their colour is
// compared as stored, alpha is not applied.
void warnIfNotOpaque(const Image& image, const std::string& name);

// Pixels with a NaN or infinite colour channel.
size_t nonFinitePixels(const Image& image);

// InputError "<name>: WxH differs from <likeName> (WxH)" when the sizes differ.
void requireSize(const Image& image, const std::string& name, const Image& like,
                 const std::string& likeName);

// Two images whose figures would mean nothing are bad input: tonemapped sRGB values against
// linear radiance, or a reference holding NaN or infinity. `linear` says which kind each holds.
void requireComparable(const std::string& testName, bool testLinear,
                       const std::string& referenceName, bool referenceLinear,
                       const Image& reference);

struct ComparisonOptions {
    // Both images hold linear radiance (an .exr), else display values (a .png): a linear image's
    // display image is tonemapped with `exposure` for FLIP and the golden-image count.
    bool linear = true;
    double exposure = 1.0;
    double ppd = flip::kDefaultPpd;
    double maxDiff = -1.0; // >= 0: count the pixels off by more than this (0-255 units)
    // Regions measured besides the whole image, by name.
    std::vector<std::pair<std::string, Mask>> regions;
};

struct Comparison {
    std::vector<std::pair<std::string, Figures>> regions; // "image" first, then the options'
    std::vector<double> ssim;                             // per pixel, rows top to bottom
    flip::Result flip;                                    // of the display images
    double diffFraction = std::numeric_limits<double>::quiet_NaN(); // with maxDiff >= 0
    size_t nonFinitePixels = 0;                                     // of the test image
};

// Throws InputError when the sizes differ (naming the images as "test" and "reference"; callers
// that know the files check requireSize first).
Comparison compareImages(const Image& test, const Image& reference,
                         const ComparisonOptions& options);

} // namespace ssgi::metrics
