// Per-pass profiling: what one frame's timestamps and host clock say, the statistics over the
// timed frames (median, min, max), the check of the passes against the host clock, and a
// Chrome/Perfetto trace. No Vulkan here: the frame graph fills FramePasses, the programs
// (render, walkthrough, the viewer) keep a ProfileLog. docs/profiling.md says how the stamps are
// made true on every device and how to read the output.
#pragma once

#include <string>
#include <vector>

namespace ssgi {

// One pass of one frame, from its timestamp pair. Times are milliseconds from the frame's first
// timestamp; a pass turned off this frame did not run and spans nothing.
struct PassTiming {
    std::string name;
    double milliseconds = 0.0;
    double startMs = 0.0, endMs = 0.0;
    bool ran = true;
    // Compute-shader invocations the pass dispatched: its workgroups times their size, lanes
    // past the image's edge and skipped pixels included, as a GPU pays for them (a pipeline
    // statistics query; 0 for a graphics pass, and where the device has no such queries).
    uint64_t invocations = 0;
};

// One frame: its passes, and the host's clock from the submission to the fence.
struct FrameProfile {
    uint32_t frame = 0;
    std::vector<PassTiming> passes;
    double hostMs = 0.0;          // submission to fence, on the host's steady clock
    double hostSubmitUs = 0.0;    // when it was submitted, microseconds on that clock
    double passSumMs() const;     // the passes added up
    uint64_t invocations() const; // every pass's invocations added up
};

struct PassStatistics {
    std::string name;
    double medianMs = 0.0, minMs = 0.0, maxMs = 0.0;
    std::vector<double> framesMs;            // each timed frame's, in order
    double medianInvocations = 0.0;          // PassTiming::invocations, the timed frames' median
    std::vector<uint64_t> framesInvocations; // each timed frame's
};

struct ProfileSummary {
    std::vector<PassStatistics> passes; // in the frame's order
    PassStatistics passSum, host;       // per frame: the passes added up; the host clock
    double worstCoverage = 1.0;         // the lowest (sum of passes / host time) of a timed frame
    uint32_t timedFrames = 0, warmupFrames = 0;
    // True where a timed frame's passes miss (or exceed) the host time by more than
    // kCoverageTolerance of it and by more than kCoverageSlackMs: the stamps are not to be
    // trusted there. (The slack is a real GPU's submission latency, which no pass covers.)
    bool disagrees = false;
};
constexpr double kCoverageTolerance = 0.03;
constexpr double kCoverageSlackMs = 0.5;

// The frames of a run. The first `warmup` frames are kept for the trace but left out of the
// statistics: the first frame carries one-time costs (lavapipe compiles shader variants at a
// pipeline's first dispatch; caches and histories start empty).
class ProfileLog {
public:
    explicit ProfileLog(uint32_t warmupFrames = 1) : warmup_(warmupFrames) {}
    void add(FrameProfile frame) { frames_.push_back(std::move(frame)); }
    // Drops all but the last `count` frames (a rolling window, as the viewer keeps).
    void keepLast(size_t count) {
        if (frames_.size() > count) frames_.erase(frames_.begin(), frames_.end() - count);
    }
    const std::vector<FrameProfile>& frames() const { return frames_; }
    uint32_t warmupFrames() const { return warmup_; }

    ProfileSummary summary() const;
    // The table --profile prints: per pass median, min and max; the sum of the passes beside the
    // host clock; a warning line when they disagree.
    std::string table(const std::string& device) const;
    // Chrome trace event format (chrome://tracing, ui.perfetto.dev): one track with the GPU
    // passes at their stamped start and end, one with each frame's submission-to-fence span on
    // the host. A frame's first stamp is placed at its submission (the two clocks are not
    // calibrated against each other; within a frame the GPU track is exact).
    std::string traceJson(const std::string& program, const std::string& device) const;

private:
    uint32_t warmup_;
    std::vector<FrameProfile> frames_;
};

} // namespace ssgi
