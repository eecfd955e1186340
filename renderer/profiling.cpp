#include "profiling.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>

namespace ssgi {

namespace {

template <class T> double median(std::vector<T> values) {
    if (values.empty()) return 0.0;
    std::sort(values.begin(), values.end());
    const size_t n = values.size();
    return n % 2 ? double(values[n / 2])
                 : 0.5 * (double(values[n / 2 - 1]) + double(values[n / 2]));
}

PassStatistics statistics(const std::string& name, std::vector<double> values,
                          std::vector<uint64_t> invocations = {}) {
    PassStatistics s{name};
    s.framesMs = values;
    s.medianInvocations = median(invocations);
    s.framesInvocations = std::move(invocations);
    if (values.empty()) return s;
    s.medianMs = median(values);
    const auto [least, most] = std::minmax_element(values.begin(), values.end());
    s.minMs = *least;
    s.maxMs = *most;
    return s;
}

// A row of the table, its name left-aligned in a column `width` wide.
std::string row(const PassStatistics& s, int width) {
    char line[256];
    // Invocations: none dispatched in any timed frame (a graphics pass, or the host's row) is "-".
    const bool any = std::any_of(s.framesInvocations.begin(), s.framesInvocations.end(),
                                 [](uint64_t n) { return n > 0; });
    char invocations[32] = "-";
    if (any) std::snprintf(invocations, sizeof invocations, "%.0f", s.medianInvocations);
    std::snprintf(line, sizeof line, "%-*s %10.3f %10.3f %10.3f %12s\n", width, s.name.c_str(),
                  s.medianMs, s.minMs, s.maxMs, invocations);
    return line;
}

} // namespace

uint64_t FrameProfile::invocations() const {
    uint64_t sum = 0;
    for (const PassTiming& p : passes)
        sum += p.invocations;
    return sum;
}

double FrameProfile::passSumMs() const {
    double sum = 0.0;
    for (const PassTiming& p : passes)
        sum += p.milliseconds;
    return sum;
}

ProfileSummary ProfileLog::summary() const {
    ProfileSummary s;
    s.warmupFrames = std::min<uint32_t>(warmup_, uint32_t(frames_.size()));
    std::vector<std::string> order;
    std::map<std::string, std::vector<double>> perPass;
    std::map<std::string, std::vector<uint64_t>> perPassInvocations;
    std::vector<double> sums, hosts;
    std::vector<uint64_t> invocations;
    for (size_t f = s.warmupFrames; f < frames_.size(); ++f) {
        const FrameProfile& frame = frames_[f];
        for (const PassTiming& p : frame.passes) {
            if (!perPass.count(p.name)) order.push_back(p.name);
            perPass[p.name].push_back(p.milliseconds);
            perPassInvocations[p.name].push_back(p.invocations);
        }
        const double sum = frame.passSumMs();
        sums.push_back(sum);
        invocations.push_back(frame.invocations());
        hosts.push_back(frame.hostMs);
        if (frame.hostMs > 0.0) {
            s.worstCoverage = std::min(s.worstCoverage, sum / frame.hostMs);
            const double miss = std::abs(frame.hostMs - sum);
            if (miss > kCoverageTolerance * frame.hostMs && miss > kCoverageSlackMs)
                s.disagrees = true;
        }
    }
    s.timedFrames = uint32_t(sums.size());
    for (const std::string& name : order)
        s.passes.push_back(statistics(name, perPass[name], perPassInvocations[name]));
    s.passSum = statistics("sum of passes", sums, invocations);
    s.host = statistics("host clock", hosts);
    return s;
}

std::string ProfileLog::table(const std::string& device) const {
    const ProfileSummary s = summary();
    std::string out = "device: " + device + "\n";
    char line[256];
    std::snprintf(line, sizeof line,
                  "%u timed frame%s after %u warm-up frame%s (left out: shader compilation at the "
                  "first dispatch, empty caches)\n",
                  s.timedFrames, s.timedFrames == 1 ? "" : "s", s.warmupFrames,
                  s.warmupFrames == 1 ? "" : "s");
    out += line;
    int width = 18; // the names' column: as wide as the longest
    for (const PassStatistics& p : s.passes)
        width = std::max(width, int(std::min<size_t>(p.name.size(), 120)));
    std::snprintf(line, sizeof line, "%-*s %10s %10s %10s %12s\n", width, "pass", "median ms",
                  "min", "max", "invocations");
    out += line;
    for (const PassStatistics& p : s.passes)
        out += row(p, width);
    out += row(s.passSum, width);
    out += row(s.host, width);
    std::snprintf(line, sizeof line,
                  "the passes cover %.1f%% of the host time (submission to fence) in the worst "
                  "timed frame\n",
                  100.0 * s.worstCoverage);
    out += line;
    if (s.disagrees)
        out += "warning: the passes and the host clock differ by more than 3% in a timed frame; "
               "the per-pass times are not to be trusted on this device\n";
    return out;
}

std::string ProfileLog::traceJson(const std::string& program, const std::string& device) const {
    using nlohmann::json;
    json events = json::array();
    auto metadata = [&](const char* what, int tid, const std::string& name) {
        json e = {{"name", what}, {"ph", "M"}, {"pid", 1}, {"args", {{"name", name}}}};
        if (tid) e["tid"] = tid;
        events.push_back(e);
    };
    metadata("process_name", 0, program + " on " + device);
    metadata("thread_name", 1, "GPU passes");
    metadata("thread_name", 2, "host: submission to fence");
    for (size_t f = 0; f < frames_.size(); ++f) {
        const FrameProfile& frame = frames_[f];
        const bool warmup = f < warmup_;
        events.push_back(
            {{"name", "frame " + std::to_string(frame.frame) + (warmup ? " (warm-up)" : "")},
             {"cat", "host"},
             {"ph", "X"},
             {"pid", 1},
             {"tid", 2},
             {"ts", frame.hostSubmitUs},
             {"dur", frame.hostMs * 1e3},
             {"args", {{"sum_of_passes_ms", frame.passSumMs()}}}});
        for (const PassTiming& p : frame.passes) {
            if (!p.ran) continue;
            events.push_back({{"name", p.name},
                              {"cat", "gpu"},
                              {"ph", "X"},
                              {"pid", 1},
                              {"tid", 1},
                              {"ts", frame.hostSubmitUs + p.startMs * 1e3},
                              {"dur", p.milliseconds * 1e3},
                              {"args", {{"frame", frame.frame}, {"warmup", warmup}}}});
        }
    }
    json trace = {{"traceEvents", events},
                  {"displayTimeUnit", "ms"},
                  {"otherData", {{"program", program}, {"device", device}}}};
    return trace.dump(1) + "\n";
}

} // namespace ssgi
