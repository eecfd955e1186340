// The settings table (settings.h) made into rows, the checks of a setting's value, and the table
// as docs/settings.md shows it.
#include "scene/settings.h"

#include "scene/scene.h"
#include "shared.h" // CACHE_COUNT_MAX: the most rotations a count holds

#include <cmath>
#include <cstdio>
#include <sstream>
#include <stdexcept>

namespace ssgi {

std::span<const SettingRow> settingTable() {
#define SSGI_SETTING_ROW(name, type, value, lo, hi, group, meaning)                                \
    SettingRow{#name,                                                                              \
               #type,                                                                              \
               double(value),                                                                      \
               double(lo),                                                                         \
               double(hi),                                                                         \
               group,                                                                              \
               meaning,                                                                            \
               [](const Settings& s) { return double(s.name); },                                   \
               [](Settings& s, double v) { s.name = static_cast<type>(v); }},
    static const SettingRow rows[] = {SSGI_SETTINGS(SSGI_SETTING_ROW)};
#undef SSGI_SETTING_ROW
    return rows;
}

namespace {

const SettingRow& findSetting(const std::string& where, const std::string& name) {
    for (const SettingRow& row : settingTable())
        if (name == row.name) return row;
    std::string known;
    for (const SettingRow& row : settingTable())
        known += std::string(" ") + row.name;
    throw InputError(where + ": unknown setting '" + name + "' (known:" + known + ")");
}

// `value` if it lies in the row's range (a whole number where the row asks for one).
double checked(const SettingRow& row, const std::string& where, double value) {
    std::ostringstream problem;
    problem << where << ": setting '" << row.name << "' is " << value << ", outside [" << row.min
            << ", " << row.max << "]";
    if (!std::isfinite(value) || value < row.min || value > row.max)
        throw InputError(problem.str());
    if (row.whole() && value != std::floor(value)) { // the refused value shown, as above
        std::ostringstream fraction;
        fraction << where << ": setting '" << row.name << "' is " << value
                 << ", and must be a whole number";
        throw InputError(fraction.str());
    }
    return value;
}

} // namespace

double checkSetting(const std::string& where, const std::string& name, double value) {
    return checked(findSetting(where, name), where, value);
}

Settings withOverrides(Settings settings, const SettingOverrides& overrides,
                       const std::string& where) {
    for (const auto& [name, value] : overrides) {
        const SettingRow& row = findSetting(where, name);
        row.set(settings, checked(row, where, value));
    }
    return settings;
}

double settingValue(const Settings& settings, const std::string& name) {
    for (const SettingRow& row : settingTable())
        if (name == row.name) return row.get(settings);
    throw std::logic_error("no setting named '" + name + "' in the settings table");
}

SettingOverrides settingValues(const Settings& settings) {
    SettingOverrides values;
    for (const SettingRow& row : settingTable())
        values[row.name] = row.get(settings);
    return values;
}

namespace {

// A number as the docs write it: 1024, 0.2, 1e-6.
std::string docNumber(double v) {
    char text[32];
    std::snprintf(text, sizeof text, "%g", v);
    std::string s = text;
    const size_t e = s.find('e');
    if (e == std::string::npos) return s;
    std::string exponent = s.substr(e + 1);
    const bool negative = exponent[0] == '-';
    exponent.erase(0, exponent.find_first_not_of("+-0"));
    return s.substr(0, e) + "e" + (negative ? "-" : "") + exponent;
}

// A flag is set as 0 or 1 (`--set cache=0`), and shown so.
std::string docDefault(const SettingRow& row) {
    if (row.flag()) return row.defaultValue != 0.0 ? "1 (on)" : "0 (off)";
    return docNumber(row.defaultValue);
}

std::string docRange(const SettingRow& row) {
    return docNumber(row.min) + (row.flag() ? ", " : " .. ") + docNumber(row.max);
}

} // namespace

std::string settingsMarkdown() {
    std::string out;
    std::string group;
    for (const SettingRow& row : settingTable()) {
        if (row.group != group) {
            group = row.group;
            out += (out.empty() ? "" : "\n") + std::string("**") + group + "**\n\n" +
                   "| setting | type | default | range | meaning |\n|---|---|---|---|---|\n";
        }
        out += std::string("| `") + row.name + "` | " + row.type + " | " + docDefault(row) + " | " +
               docRange(row) + " | " + row.meaning + " |\n";
    }
    return out;
}

float aoRadius(const Scene& scene) {
    const double radius = scene.settings.ao_radius;
    // With the sky's visibility (and AO, not SSDO), its depth maps see every occluder they
    // resolve, and they see it better than the screen does (docs/effects.md, "AO and the sky's
    // visibility"): the AO is left what is too near for them, about three of their texels.
    // Without them the AO stands for all of the sky's occlusion and reaches further.
    const double diagonal =
        scene.aoDiagonal > 0.0f ? scene.aoDiagonal : glm::length(scene.bounds.size());
    const double derived = (hasSkyVisibility(scene) ? 0.0125 : 0.05) * diagonal;
    return float(radius > 0.0 ? radius : (derived > 0.0 ? derived : 0.1));
}

bool hasSkyVisibility(const Scene& scene) {
    const bool blackSky = scene.sky.zenith == glm::vec3(0.0f) &&
                          scene.sky.horizon == glm::vec3(0.0f) &&
                          scene.sky.ground == glm::vec3(0.0f);
    return scene.settings.sky_visibility && !scene.settings.ssdo && !blackSky;
}

bool skyInWorldCache(const Scene& scene) {
    const Settings& s = scene.settings;
    return hasSkyVisibility(scene) && s.indirect && s.indirect_method == 3 &&
           s.world_sky_visibility;
}

} // namespace ssgi
