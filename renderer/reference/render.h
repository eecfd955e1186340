// Progressive, multi-threaded rendering of a reference image: passes of samples over every
// pixel until a sample count or a noise target is reached, reproducible from the seed alone.
#pragma once

#include "reference/integrator.h"

#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

namespace ssgi::reference {

// The noise target stops no render before every pixel has this many samples.
constexpr uint32_t kMinSamplesForNoise = 16;

// What the reference program renders when not told otherwise: samples until the estimated noise
// is 1% (its own relMSE about 1e-4), at most 65536 a pixel: the Cornell box, the slowest of the
// shipped scenes to converge, needs about 21000.
constexpr double kDefaultNoiseTarget = 0.01;
// The smallest noise target taken (0 is none): below it no cap of samples reaches it.
constexpr double kMinNoiseTarget = 1e-6;
constexpr uint32_t kDefaultSampleCap = 65536;

struct ReferenceOptions {
    Mode mode = Mode::Full;
    uint32_t width = 128, height = 128;
    uint32_t spp = 64; // stop after this many samples per pixel
    // Also stop once the estimated noise is this low (0: never), after kMinSamplesForNoise samples
    // and on an estimate above 0 (unless no sample draws a random number).
    double noiseTarget = 0.0;
    uint64_t seed = 1;
    // Random sub-pixel positions (anti-aliased edges). Off, every sample goes through the
    // pixel centre, as the real-time G-buffer samples, so edges match pixel for pixel.
    bool jitter = false;
    unsigned threads = 0;  // 0: every hardware thread; the image does not depend on it
    bool progress = false; // a progress bar on stderr
    // Called about every 50 ms while a pass renders, and after each pass, with what show()
    // is given: samples done, the pass's end, the fraction of its rows done, the noise.
    // Returning false stops the render: renderReference throws Cancelled. For a host that
    // shows progress its own way, or stops on a signal (the Python module).
    std::function<bool(uint32_t done, uint32_t passEnd, double passFraction, double noise)>
        onProgress;
};

// Thrown by renderReference when onProgress asked it to stop.
struct Cancelled : std::runtime_error {
    Cancelled() : std::runtime_error("the reference render was stopped") {}
};

struct ReferenceImage {
    uint32_t width = 0, height = 0;
    uint32_t samples = 0; // per pixel
    // Estimated remaining noise: the root mean over pixels of (standard error of the pixel's
    // luminance)^2 / (luminance^2 + 0.01), i.e. the expected relative error (sqrt relMSE)
    // against the converged image.
    double noise = 0.0;
    uint64_t nonFiniteSamples = 0; // dropped NaN/Inf samples (should stay 0)
    std::vector<float> rgba;       // rows top to bottom; a = fraction of samples on geometry
};

// The camera ray through pixel position (px, py) in pixels (pixel centres at +0.5): from the
// near plane to the far plane of projectionMatrix(camera, W/H) * viewMatrix(camera), exactly
// where the rasteriser puts that sample.
struct CameraRays {
    CameraRays(const Camera& camera, uint32_t width, uint32_t height);
    void ray(float px, float py, glm::vec3& origin, glm::vec3& direction, float& tfar) const;

private:
    glm::dmat4 inverseViewProjection_;
    double width_, height_;
};

// Throws InputError for a zero size or zero spp.
ReferenceImage renderReference(const Scene& scene, const Camera& camera,
                               const ReferenceOptions& options);

} // namespace ssgi::reference
