// The method settings: one table of defaults and ranges serves the scene file, `render --set`
// and the passes. Lengths whose default is 0 are derived from the scene's own size, so a scene
// file names only what differs and one default serves every scale.
#include "scene/scene.h"

#include <cmath>
#include <sstream>

namespace ssgi {

const std::map<std::string, SettingSpec>& settingSpecs() {
    static const std::map<std::string, SettingSpec> specs = {
        {"shadow_map_size", {1024, 16, 8192, true, "RSM resolution, texels per side"}},
        {"exposure", {1.0, 1e-6, 1e6, false, "multiplies radiance before tonemapping"}},
        // Read while loading (docs/bare-models.md): a scene file's default is no ground.
        {"ground_plane",
         {1, 0, 1, true, "a ground under a bare glTF without a floor; scene files: when set"}},
        {"shadow_bias", {1.5, 0, 100, false, "normal offset of the shadow lookup, in texels"}},
        {"shadow_taps", {49, 1, 64, true, "PCF taps (1 = hard shadow; thesis: 49, or 9 + cache)"}},
        {"ao", {1, 0, 1, true, "ambient occlusion on (1) or off (0)"}},
        {"ao_variant", {0, 0, 2, true, "0 thesis (eq. 6-8), 1 Crytek/Mittring, 2 horizon (GTAO)"}},
        {"ao_radius", {0, 0, 1e9, false, "AO radius in scene units; 0 = 5% of the scene diagonal"}},
        {"ao_directions", {8, 1, 32, true, "AO sampling directions per pixel"}},
        {"ao_steps", {4, 1, 32, true, "AO samples per direction (log-spaced, eq. 8)"}},
        {"ao_attenuation_a", {1.0, 0, 1e3, false, "a in D(d) = 1 + a d + b d^2, d in AO radii"}},
        {"ao_attenuation_b", {0.0, 0, 1e3, false, "b in D(d) = 1 + a d + b d^2, d in AO radii"}},
        {"indirect", {1, 0, 1, true, "one-bounce indirect light from the RSM on (1) or off (0)"}},
        {"indirect_method",
         {1, 0, 1, true,
          "0 the thesis's half-resolution gather + upsampling, 1 interleaved VPL subsets"}},
        {"indirect_vpls",
         {512, 1, 1024, true, "VPLs of the pattern (method 0: each pixel's; 1: each block's)"}},
        {"indirect_interleave",
         {4, 1, 8, true, "method 1: k, blocks of k x k pixels split the VPLs into k^2 subsets"}},
        {"indirect_filter_radius",
         {8, 1, 32, true, "method 1: reach in pixels of the geometry-aware filter, per axis"}},
        {"indirect_radius",
         {0.0, 0, 2, false, "VPL sampling radius in RSM uv; 0 = reach the whole map"}},
        {"indirect_visibility", {1, 0, 1, true, "screen-space visibility test of each VPL"}},
        {"indirect_visibility_steps", {6, 1, 32, true, "log-spaced steps of the visibility test"}},
        {"indirect_half_res", {1, 0, 1, true, "method 0: gather at half resolution (1) or full (0)"}},
        {"cache", {1, 0, 1, true, "temporal cache of shadow, AO, SSDO and indirect light"}},
        {"cache_shadow",
         {1, 0, 1, true, "the shadow term cached (1), or computed anew each frame"}},
        {"cache_ao", {1, 0, 1, true, "the AO cached (1), or computed anew each frame"}},
        {"cache_ssdo", {1, 0, 1, true, "SSDO cached (1), or computed anew each frame"}},
        {"cache_indirect", {1, 0, 1, true, "the indirect light cached (1), or computed anew"}},
        {"cache_method",
         {0, 0, 1, true, "0 the thesis's confidence rule (eq. 4-5), 1 running mean"}},
        {"cache_bias", {0.0, 0, 1e3, false, "bias of the confidence rule (eq. 4)"}},
        {"cache_epsilon", {2.0, 0, 1e3, false, "reprojection test (eq. 3), in pixel footprints"}},
        {"cache_rotations", {36, 1, 1e6, true, "pattern rotations until a pixel is converged"}},
        // Automatic camera cuts: a turn or a jump this large between two frames restarts every
        // history, as engines reset temporal effects on a cut.
        {"cache_cut_angle_deg",
         {45.0, 0, 180, false, "a camera turn beyond this between frames is a cut (180: never)"}},
        {"cache_cut_distance",
         {0.2, 0, 1e9, false, "a camera jump beyond this x scene diagonal is a cut (huge: never)"}},
        {"cache_rotation_deg", {10.0, -360, 360, false, "turn of every sampling pattern a frame"}},
        {"cache_scale_jitter", {0.1, 0, 0.9, false, "relative change of pattern size a frame"}},
        {"cache_refresh", {1, 0, 1, true, "tiled refresh: one tile a frame computed anew"}},
        {"cache_tile_shadow", {64, 1, 4096, true, "refresh tile size of the shadow (pixels)"}},
        {"cache_tile_ao", {64, 1, 4096, true, "refresh tile size of the AO (pixels)"}},
        {"cache_tile_ssdo", {64, 1, 4096, true, "refresh tile size of SSDO (pixels)"}},
        {"cache_tile_indirect", {16, 1, 4096, true, "refresh tile size of the indirect light"}},
        // How much resampling blur (squared pixels) a moving camera may leave in each effect's
        // history before its weight is cut and the pixel computed again: none in the sharp
        // shadow term, more in the smooth AO, SSDO and indirect light.
        {"cache_blur_shadow", {0.0, 0, 1e6, false, "shadow history's blur budget (pixels^2)"}},
        {"cache_blur_ao", {2.0, 0, 1e6, false, "AO history's blur budget (pixels^2)"}},
        {"cache_blur_ssdo", {2.0, 0, 1e6, false, "SSDO history's blur budget (pixels^2)"}},
        {"cache_blur_indirect", {4.0, 0, 1e6, false, "indirect history's blur budget (px^2)"}},
        {"ssdo", {0, 0, 1, true, "SSDO replaces AO: directional sky occlusion + one bounce"}},
        {"sky_visibility",
         {1, 0, 1, true, "the sky occluded beyond the AO radius, from depth maps over the sky"}},
        {"sky_visibility_directions",
         {64, 1, 1024, true, "directions (depth maps) of the sky visibility, over the sphere"}},
        {"sky_visibility_map_size",
         {256, 16, 4096, true, "texels per side of each sky visibility depth map"}},
        {"ssdo_samples", {16, 1, 64, true, "SSDO hemisphere samples per pixel"}},
        {"ssdo_radius", {0, 0, 1e9, false, "SSDO r_max in scene units; 0 = the AO radius"}},
        {"ssdo_bounce", {1.0, 0, 1e3, false, "SSDO one-bounce strength (the paper's user factor)"}},
        {"depth_peeling",
         {0, 0, 1, true, "SSDO and contact shadows test occlusion between two depth layers"}},
        {"contact_shadows", {0, 0, 1, true, "screen-space contact shadows on the shadow term"}},
        {"contact_shadow_steps", {8, 1, 64, true, "samples along the contact-shadow segment"}},
        {"contact_shadow_texels", {6, 0, 1e3, false, "contact-shadow segment, shadow-map texels"}},
    };
    return specs;
}

double checkSetting(const std::string& where, const std::string& key, double value) {
    auto it = settingSpecs().find(key);
    if (it == settingSpecs().end()) {
        std::string known;
        for (const auto& spec : settingSpecs())
            known += " " + spec.first;
        throw InputError(where + ": unknown setting '" + key + "' (known:" + known + ")");
    }
    const SettingSpec& spec = it->second;
    std::ostringstream problem;
    problem << where << ": setting '" << key << "' is " << value << ", outside [" << spec.min
            << ", " << spec.max << "]";
    if (!std::isfinite(value) || value < spec.min || value > spec.max)
        throw InputError(problem.str());
    if (spec.whole && value != std::floor(value))
        throw InputError(where + ": setting '" + key + "' must be a whole number");
    return value;
}

double Scene::setting(const std::string& key) const {
    auto it = settings.find(key);
    return it != settings.end() ? it->second : settingSpecs().at(key).defaultValue;
}

float aoRadius(const Scene& scene) {
    const double radius = scene.setting("ao_radius");
    const double derived = 0.05 * glm::length(scene.bounds.size());
    return float(radius > 0.0 ? radius : (derived > 0.0 ? derived : 0.1));
}

} // namespace ssgi
