#include "reference/render.h"

#include "metrics/metrics.h"
#include "reference/progress.h"
#include "scene/camera.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <string>
#include <sys/resource.h>
#include <thread>
#include <unistd.h>

namespace ssgi::reference {
namespace {

// Most samples in one pass: passes stay short enough for the bar and the noise estimate to
// move, long enough that starting threads costs nothing.
constexpr uint32_t kLargestPass = 32;

// What one pixel costs while it renders: its running sums and its value in the image returned.
constexpr double kBytesPerPixel = 56.0 + 16.0;
// The most of the available memory a render may take.
constexpr double kUsableMemory = 0.8;

// Running sums of one pixel, in double so that thousands of samples add without drift.
struct PixelSums {
    glm::dvec3 sum{0.0};
    double coverage = 0.0;
    double meanLuminance = 0.0, squaredDeviations = 0.0; // Welford
    uint32_t count = 0;
};

double luminance(glm::vec3 c) {
    return 0.2126 * c.r + 0.7152 * c.g + 0.0722 * c.b;
}

double noiseOf(const std::vector<PixelSums>& pixels) {
    double total = 0.0;
    for (const PixelSums& p : pixels) {
        if (p.count < 2) return INFINITY;
        const double varianceOfMean = p.squaredDeviations / double(p.count - 1) / double(p.count);
        total += varianceOfMean / (p.meanLuminance * p.meanLuminance + metrics::kRelMseEpsilon);
    }
    return pixels.empty() ? 0.0 : std::sqrt(total / double(pixels.size()));
}

// Samples [first, last) of every pixel of one row; nothing here depends on the thread.
void renderRow(const Integrator& integrator, const CameraRays& camera,
               const ReferenceOptions& options, uint32_t y, uint32_t first, uint32_t last,
               std::vector<PixelSums>& pixels, std::atomic<uint64_t>& nonFinite) {
    for (uint32_t x = 0; x < options.width; ++x) {
        const uint64_t index = uint64_t(y) * options.width + x;
        PixelSums& p = pixels[index];
        for (uint32_t s = first; s < last; ++s) {
            Rng rng(options.seed, index, s);
            const glm::vec2 offset = options.jitter ? rng.uniform2() : glm::vec2(0.5f);
            glm::vec3 origin, direction;
            float tfar;
            camera.ray(float(x) + offset.x, float(y) + offset.y, origin, direction, tfar);
            const glm::vec4 value = integrator.cameraSample(origin, direction, tfar, rng);
            if (!std::isfinite(value.r + value.g + value.b)) {
                ++nonFinite;
                continue;
            }
            p.sum += glm::dvec3(value);
            p.coverage += value.a;
            ++p.count;
            const double l = luminance(glm::vec3(value));
            const double delta = l - p.meanLuminance;
            p.meanLuminance += delta / double(p.count);
            p.squaredDeviations += delta * (l - p.meanLuminance);
        }
    }
}

// Whether the noise target is met. A pixel whose first samples all missed what lights it (a
// rare path to a narrow spot light) has no variance yet and looks converged: the estimate is
// believed only after kMinSamplesForNoise samples of every pixel, and an estimate of exactly 0
// (no pixel's samples ever differed) only where no sample draws a random number.
bool noiseTargetMet(const ReferenceOptions& options, uint32_t done, double noise, bool exact) {
    if (!(options.noiseTarget > 0.0) || !(noise <= options.noiseTarget)) return false;
    return exact || (done >= kMinSamplesForNoise && noise > 0.0);
}

// How many samples the next pass takes: doubling, and no more than the stopping rules need.
uint32_t nextPassSize(const ReferenceOptions& options, uint32_t done, double noise) {
    uint32_t size = std::clamp(done, 2u, kLargestPass);
    if (options.noiseTarget > 0.0 && std::isfinite(noise) && noise > 0.0 &&
        done >= kMinSamplesForNoise) {
        const double needed =
            double(done) * (noise / options.noiseTarget) * (noise / options.noiseTarget);
        size = uint32_t(std::clamp(std::ceil(needed - double(done)), 1.0, double(size)));
    }
    return std::min(size, options.spp - done);
}

// Memory this process may take: the least of the memory available (MemAvailable, else the
// physical memory), its cgroup's room (memory.max - memory.current, cgroup v2) and its limits on
// address space and data (ulimit -v, -d).
double availableBytes() {
    double bytes = double(sysconf(_SC_PHYS_PAGES)) * double(sysconf(_SC_PAGESIZE));
    {
        std::ifstream meminfo("/proc/meminfo");
        std::string name;
        double kib = 0.0;
        while (meminfo >> name >> kib) {
            if (name == "MemAvailable:") bytes = kib * 1024.0;
            meminfo.ignore(256, '\n');
        }
    }
    double limit = 0.0, current = 0.0;
    if ((std::ifstream("/sys/fs/cgroup/memory.max") >> limit) &&
        (std::ifstream("/sys/fs/cgroup/memory.current") >> current))
        bytes = std::min(bytes, std::max(limit - current, 0.0)); // "max" reads as no number
    for (int resource : {RLIMIT_AS, RLIMIT_DATA}) {
        rlimit r{};
        if (getrlimit(resource, &r) == 0 && r.rlim_cur != RLIM_INFINITY)
            bytes = std::min(bytes, double(r.rlim_cur));
    }
    return bytes;
}

std::string gigabytes(double bytes) {
    char text[32];
    std::snprintf(text, sizeof text, "%.1f GB", bytes / 1e9);
    return text;
}

} // namespace

CameraRays::CameraRays(const Camera& camera, uint32_t width, uint32_t height)
    : width_(width), height_(height) {
    const glm::mat4 viewProjection =
        projectionMatrix(camera, float(width) / float(height)) * viewMatrix(camera);
    inverseViewProjection_ = glm::inverse(glm::dmat4(viewProjection));
}

void CameraRays::ray(float px, float py, glm::vec3& origin, glm::vec3& direction,
                     float& tfar) const {
    const double nx = 2.0 * double(px) / width_ - 1.0, ny = 2.0 * double(py) / height_ - 1.0;
    const glm::dvec4 nearPoint = inverseViewProjection_ * glm::dvec4(nx, ny, 0.0, 1.0);
    const glm::dvec4 farPoint = inverseViewProjection_ * glm::dvec4(nx, ny, 1.0, 1.0);
    const glm::dvec3 a = glm::dvec3(nearPoint) / nearPoint.w;
    const glm::dvec3 b = glm::dvec3(farPoint) / farPoint.w;
    origin = glm::vec3(a);
    direction = glm::vec3(glm::normalize(b - a));
    tfar = float(glm::length(b - a));
}

ReferenceImage renderReference(const Scene& scene, const Camera& camera,
                               const ReferenceOptions& options) {
    if (options.width == 0 || options.height == 0)
        throw InputError("--size: the image must be at least 1x1");
    if (options.spp == 0) throw InputError("--spp: must be at least 1");
    if (options.noiseTarget > 0.0 && options.noiseTarget < kMinNoiseTarget) {
        char text[96];
        std::snprintf(text, sizeof text, "--noise: %g is below %g (0: no noise target)",
                      options.noiseTarget, kMinNoiseTarget);
        throw InputError(text);
    }
    // Refused before anything is allocated: an allocation the machine cannot back either throws
    // after seconds of paging or gets the process killed. A fifth of what is available is left
    // to the rest of the program and to everything else on the machine.
    const double pixelCount = double(options.width) * double(options.height);
    const double needed = pixelCount * kBytesPerPixel, available = availableBytes();
    if (needed > kUsableMemory * available)
        throw InputError("--size " + std::to_string(options.width) + "x" +
                         std::to_string(options.height) + ": the reference needs " +
                         gigabytes(needed) + " of memory for its " +
                         std::to_string(uint64_t(pixelCount)) + " pixels (" +
                         std::to_string(int(kBytesPerPixel)) + " bytes each), more than " +
                         gigabytes(kUsableMemory * available) + " (80% of the " +
                         gigabytes(available) + " available); render it smaller");
    const RayScene rays(scene);
    const Integrator integrator(scene, rays, options.mode);
    const bool exact = integrator.drawsNoRandomNumber() && !options.jitter;
    const CameraRays cameraRays(camera, options.width, options.height);
    const unsigned threads =
        options.threads ? options.threads : std::max(1u, std::thread::hardware_concurrency());

    std::vector<PixelSums> pixels(size_t(options.width) * options.height);
    std::atomic<uint64_t> nonFinite{0};
    Progress progress(options.progress, options.spp, options.noiseTarget);
    uint32_t done = 0;
    double noise = INFINITY;
    while (done < options.spp && !noiseTargetMet(options, done, noise, exact)) {
        const uint32_t last = done + nextPassSize(options, done, noise);
        std::atomic<uint32_t> nextRow{0}, rowsDone{0};
        auto work = [&] {
            for (uint32_t y; (y = nextRow++) < options.height; ++rowsDone)
                renderRow(integrator, cameraRays, options, y, done, last, pixels, nonFinite);
        };
        std::vector<std::thread> workers;
        for (unsigned t = 0; t < threads; ++t)
            workers.emplace_back(work);
        // Only a visible bar or a host's callback is worth polling for; otherwise the pass ends
        // when its rows do.
        bool stopped = false;
        while ((options.progress || options.onProgress) && rowsDone.load() < options.height) {
            const double fraction = double(rowsDone.load()) / options.height;
            progress.show(done, last, fraction, noise);
            if (options.onProgress && !options.onProgress(done, last, fraction, noise)) {
                stopped = true;
                nextRow = options.height; // the workers take no further row
                break;
            }
            std::this_thread::sleep_for(std::chrono::milliseconds(options.progress ? 50 : 10));
        }
        for (std::thread& worker : workers)
            worker.join();
        if (stopped) throw Cancelled();
        done = last;
        noise = noiseOf(pixels);
        progress.show(done, done, 0.0, noise);
        if (options.onProgress && !options.onProgress(done, done, 0.0, noise)) throw Cancelled();
    }
    progress.finish(done, noise);

    ReferenceImage image;
    image.width = options.width;
    image.height = options.height;
    image.samples = done;
    image.noise = noise;
    image.nonFiniteSamples = nonFinite.load();
    image.rgba.resize(pixels.size() * 4);
    for (size_t i = 0; i < pixels.size(); ++i) {
        const double n = std::max(pixels[i].count, 1u);
        const glm::dvec3 mean = pixels[i].sum / n;
        image.rgba[4 * i + 0] = float(mean.r);
        image.rgba[4 * i + 1] = float(mean.g);
        image.rgba[4 * i + 2] = float(mean.b);
        image.rgba[4 * i + 3] = float(pixels[i].coverage / n);
    }
    return image;
}

} // namespace ssgi::reference
