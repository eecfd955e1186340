#include "configs.h"

#include <algorithm>
#include <stdexcept>
#include <utility>

namespace ssgi::bench {

std::vector<Axis> makeAxes() {
    Axis ao{"ao", {"ao", "ssdo"}, {}};
    // ao_variant's values by name; horizon (GTAO, the default) first, so that the axis's first
    // value is the renderer's default AO.
    const char* variants[] = {"thesis AO", "Crytek AO", "horizon AO"};
    const int sizes[][2] = {{8, 4}, {4, 2}, {16, 4}};
    for (int variant : {2, 0, 1})
        for (const auto& size : sizes)
            ao.values.push_back({std::string(variants[variant]) + " " + std::to_string(size[0]) +
                                     "x" + std::to_string(size[1]),
                                 {{"ao", 1},
                                  {"ssdo", 0},
                                  {"ao_variant", variant},
                                  {"ao_directions", size[0]},
                                  {"ao_steps", size[1]}}});
    for (int samples : {16, 8, 32})
        ao.values.push_back(
            {"SSDO " + std::to_string(samples), {{"ssdo", 1}, {"ssdo_samples", samples}}});
    ao.values.push_back({"no AO", {{"ao", 0}, {"ssdo", 0}}});
    ao.off = ao.values.size() - 1;

    // The gather first: the ceiling table times the first of these a configuration runs.
    Axis indirect{"indirect",
                  {"indirect", "upsample", "indirect.filter_x", "indirect.filter_y",
                   "indirect.flux", "indirect.vpls"},
                  {}};
    // Interleaved subsets of 4 x 4 with the geometry-aware filter (indirect_method 1, the
    // default: the axis's first value): the same VPL sets at 1/16 of the VPLs per pixel. Then
    // importance (indirect_method 2): the same subsets over the RSM clustered into a VPL map,
    // beside VPLs drawn by flux, the visibility test on the candidates with the most light.
    const std::pair<int, const char*> subsetMethods[] = {{1, "interleaved"}, {2, "importance"}};
    for (const auto& [method, name] : subsetMethods)
        for (int vpls : {384, 512, 256, 128})
            indirect.values.push_back({std::to_string(vpls) + " VPLs + visibility, " + name,
                                       {{"indirect", 1},
                                        {"indirect_method", method},
                                        {"indirect_vpls", vpls},
                                        {"indirect_visibility", 1}}});
    // The thesis's gather (indirect_method 0). 1024 VPLs only without the visibility test: with
    // it, one frame costs as much as all the other rows together on lavapipe, and the thesis
    // stops at 512.
    for (int visibility : {1, 0})
        for (int vpls : {512, 64, 128, 256, 1024})
            if (!(visibility && vpls == 1024))
                indirect.values.push_back(
                    {std::to_string(vpls) + " VPLs" + (visibility ? " + visibility" : ""),
                     {{"indirect", 1},
                      {"indirect_method", 0},
                      {"indirect_vpls", vpls},
                      {"indirect_visibility", visibility},
                      {"indirect_half_res", 1}}});
    // Gathered at full resolution (no half-res pass, no upsampling): what half resolution saves.
    for (int vpls : {512, 128})
        indirect.values.push_back({std::to_string(vpls) + " VPLs + visibility, full res",
                                   {{"indirect", 1},
                                    {"indirect_method", 0},
                                    {"indirect_vpls", vpls},
                                    {"indirect_visibility", 1},
                                    {"indirect_half_res", 0}}});
    indirect.values.push_back({"no indirect", {{"indirect", 0}}});
    indirect.off = indirect.values.size() - 1;

    // The light-space horizons (the default), the thesis's PCSS at 49 and 9 taps, the hard test.
    Axis shadow{"shadow", {"shadow"}, {}};
    shadow.values.push_back(
        {"horizons 12x6", {{"shadow_variant", 1}, {"shadow_directions", 12}, {"shadow_steps", 6}}});
    for (int taps : {49, 9, 1})
        shadow.values.push_back({taps == 1 ? "hard shadow" : "PCF " + std::to_string(taps),
                                 {{"shadow_variant", 0}, {"shadow_taps", taps}}});
    shadow.off = shadow.values.size() - 1;
    return {ao, indirect, shadow};
}

size_t indexOf(const Axis& axis, const std::string& label) {
    for (size_t v = 0; v < axis.values.size(); ++v)
        if (axis.values[v].label == label) return v;
    throw std::logic_error("no value '" + label + "' on axis " + axis.name);
}

SettingOverrides settingsOf(const std::vector<Axis>& axes, const Index& index) {
    SettingOverrides s = {{"cache", 0}};
    for (size_t a = 0; a < axes.size(); ++a)
        for (const auto& [key, value] : axes[a].values[index[a]].settings)
            s[key] = value;
    return s;
}

std::string labelOf(const std::vector<Axis>& axes, const Index& index) {
    std::string label;
    for (size_t a = 0; a < axes.size(); ++a)
        label += (a ? " + " : "") + axes[a].values[index[a]].label;
    return label;
}

std::vector<Config> makeConfigs(const std::vector<Axis>& axes) {
    std::vector<Config> configs = {{"default", {0, 0, 0}}};
    for (size_t a = 0; a < axes.size(); ++a)
        for (size_t v = 1; v < axes[a].values.size(); ++v) {
            Config c{axes[a].name, {0, 0, 0}};
            c.index[a] = v;
            configs.push_back(c);
        }
    const size_t cheapAo = indexOf(axes[kAo], "thesis AO 4x2");
    const size_t pcf9 = indexOf(axes[kShadow], "PCF 9");
    for (size_t v = 0; v < axes[kIndirect].values.size(); ++v)
        configs.push_back({"cheap", {cheapAo, v, pcf9}});
    configs.push_back({"direct only", {axes[kAo].off, axes[kIndirect].off, pcf9}});
    return configs;
}

TimingPlan makeTimingPlan(const std::vector<Axis>& axes) {
    TimingPlan plan;
    plan.rowOf.resize(axes.size());
    auto row = [&](const Index& index) {
        auto found = std::find(plan.rows.begin(), plan.rows.end(), index);
        if (found != plan.rows.end()) return size_t(found - plan.rows.begin());
        plan.rows.push_back(index);
        return plan.rows.size() - 1;
    };
    const size_t none = axes[kIndirect].off;
    for (size_t v = 0; v < axes[kIndirect].values.size(); ++v) // base A, the indirect varied
        plan.rowOf[kIndirect].push_back(row({0, v, 0}));
    for (size_t v = 0; v < axes[kAo].values.size(); ++v) // base B, the AO varied
        plan.rowOf[kAo].push_back(row({v, none, 0}));
    for (size_t v = 0; v < axes[kShadow].values.size(); ++v) // base B, the shadow varied
        plan.rowOf[kShadow].push_back(row({0, none, v}));
    plan.check = row({indexOf(axes[kAo], "thesis AO 4x2"), indexOf(axes[kIndirect], "256 VPLs"),
                      indexOf(axes[kShadow], "PCF 9")});
    return plan;
}

} // namespace ssgi::bench
