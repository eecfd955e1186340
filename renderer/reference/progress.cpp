#include "reference/progress.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <unistd.h>

namespace ssgi::reference {

Progress::Progress(bool enabled, uint32_t sppLimit, double noiseTarget)
    : enabled_(enabled), terminal_(isatty(fileno(stderr)) != 0), sppLimit_(sppLimit),
      noiseTarget_(noiseTarget) {}

// Noise falls as 1/sqrt(samples), so the samples the target needs are n (noise/target)^2; the
// render is as far along as the nearer of its two stopping rules.
double Progress::fractionDone(double samples, double noise) const {
    double fraction = samples / double(sppLimit_);
    if (noiseTarget_ > 0.0 && std::isfinite(noise) && noiseAt_ > 0) {
        const double needed = double(noiseAt_) * (noise / noiseTarget_) * (noise / noiseTarget_);
        fraction = std::max(fraction, samples / std::max(needed, 1.0));
    }
    return std::clamp(fraction, 0.0, 1.0);
}

void Progress::show(uint32_t done, uint32_t passEnd, double passFraction, double noise) {
    if (!enabled_) return;
    const bool passEnded = passEnd == done; // called at the end of a pass with its noise
    if (passEnded) noiseAt_ = done;
    // A log file gets one line per pass, not a redrawn bar every few milliseconds.
    if (!terminal_ && !passEnded) return;
    const double samples = done + (passEnd - done) * passFraction;
    const double fraction = fractionDone(samples, noise);
    const double elapsed =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    constexpr int kWidth = 30;
    const int filled = int(fraction * kWidth);
    const std::string bar =
        std::string(size_t(filled), '#') + std::string(size_t(kWidth - filled), '.');
    char noiseText[32] = "noise   ?  ";
    if (std::isfinite(noise))
        std::snprintf(noiseText, sizeof noiseText, "noise %5.2f%%", 100.0 * noise);
    char left[32] = "";
    if (fraction > 0.0)
        std::snprintf(left, sizeof left, "%6.1f s left", elapsed * (1.0 / fraction - 1.0));
    std::fprintf(stderr, "%s[%s] %3d%%  %5.0f/%u spp  %s  %s%s", terminal_ ? "\r" : "", bar.c_str(),
                 int(100.0 * fraction), samples, sppLimit_, noiseText, left,
                 terminal_ ? " " : "\n");
    std::fflush(stderr);
}

void Progress::finish(uint32_t done, double noise) {
    if (!enabled_) return;
    const double elapsed =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    if (terminal_) std::fprintf(stderr, "\r%100s\r", "");
    if (std::isfinite(noise))
        std::fprintf(stderr, "done: %u spp, noise %.2f%% (estimated relative error), %.1f s\n",
                     done, 100.0 * noise, elapsed);
    else
        std::fprintf(stderr, "done: %u spp (too few to estimate the noise), %.1f s\n", done,
                     elapsed);
}

} // namespace ssgi::reference
