// The configurations of the sweep: three axes of method settings (AO/SSDO, indirect light,
// shadow), the configurations taken from them, and the rows that are timed. A configuration's
// time is composed from the rows by bench/analysis.py: each pass from the rows that time its
// value.
#pragma once

#include "bench.h"

namespace ssgi::bench {

struct AxisValue {
    std::string label;
    SettingOverrides settings;
};

struct Axis {
    std::string name;
    std::vector<std::string> passes; // the passes whose time depends on this axis only
    std::vector<AxisValue> values;   // the default first
    size_t off = 0;                  // the value without the pass, or its cheapest
};

enum AxisId : size_t { kAo, kIndirect, kShadow };
using Index = std::vector<size_t>; // one value per axis

std::vector<Axis> makeAxes();
size_t indexOf(const Axis& axis, const std::string& label);
SettingOverrides settingsOf(const std::vector<Axis>& axes, const Index& index);
std::string labelOf(const std::vector<Axis>& axes, const Index& index);

struct Config {
    std::string group;
    Index index;
};
// The defaults; each axis varied alone; the cheap side (4x2 AO, PCF 9) with every indirect
// setting; direct light alone.
std::vector<Config> makeConfigs(const std::vector<Axis>& axes);

// The timed rows. The AO and shadow values are timed without indirect light (base B: default
// AO, no indirect, PCF 49), so that their small costs are not lost in its noise; the indirect
// values with the default AO and shadow (base A). The last row is a check, away from every
// default, whose measured time the composition must predict.
struct TimingPlan {
    std::vector<Index> rows;
    std::vector<std::vector<size_t>> rowOf; // [axis][value]: the row that times that value
    size_t check = 0;                       // the check row
};
TimingPlan makeTimingPlan(const std::vector<Axis>& axes);

} // namespace ssgi::bench
