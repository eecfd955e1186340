// The progress bar of a reference render on stderr: samples done, the estimated remaining
// noise, and the time left until the first stopping rule (sample count or noise) is met.
#pragma once

#include <chrono>
#include <cstdint>

namespace ssgi::reference {

class Progress {
public:
    Progress(bool enabled, uint32_t sppLimit, double noiseTarget);
    // `done` samples complete, a pass toward `passEnd` `passFraction` of the way through.
    void show(uint32_t done, uint32_t passEnd, double passFraction, double noise);
    void finish(uint32_t done, double noise);

private:
    double fractionDone(double samples, double noise) const;

    bool enabled_;
    bool terminal_; // stderr is a terminal: redraw one line in place
    uint32_t sppLimit_;
    double noiseTarget_;
    uint32_t noiseAt_ = 0; // the sample count at which `noise` was measured
    std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
};

} // namespace ssgi::reference
