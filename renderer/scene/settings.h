// The method settings, each declared once in SSGI_SETTINGS: its name (also its member of
// Settings), type, default, range, group and one-line meaning. The typed struct, the checks of
// scene files and `--set`, the viewer's panel and the table in docs/settings.md all follow from
// that one list; the renderer reads the struct's members. Adding a setting is one row here plus
// its use (docs/settings.md: "Adding a setting").
#pragma once

#include <map>
#include <span>
#include <string>
#include <string_view>

namespace ssgi {

// X(name, type, default, min, max, group, meaning). Types: bool (on/off), int (a whole number),
// double. Lengths whose default is 0 are derived from the scene's own size, so a scene file
// names only what differs and one default serves every scale.
#define SSGI_SETTINGS(X)                                                                           \
    X(exposure, double, 1.0, 1e-6, 1e6, "Image", "multiplies radiance before tonemapping")         \
    X(ground_plane, int, -1, -1, 1, "Image",                                                       \
      "a ground plane under a model without a floor of its own: 1 yes, 0 no, -1 only under a "     \
      "bare glTF (read while loading; docs/bare-models.md)")                                       \
    X(guard_band, int, 0, 0, 256, "Image",                                                         \
      "pixels rendered beyond each edge of the image, for the screen-space effects to see what "   \
      "lies just off screen (0: none; docs/frame.md)")                                             \
    X(shadow_map_size, int, 2048, 16, 8192, "Shadow",                                              \
      "the shadow test's depth map from the light, texels per side (the RSM's own depth when "     \
      "equal to rsm_size)")                                                                        \
    X(shadow_bias, double, 3, 0, 100, "Shadow",                                                    \
      "normal offset of the shadow lookup, in texels, times the cosine at which the light "        \
      "meets the surface")                                                                         \
    X(shadow_variant, int, 1, 0, 1, "Shadow",                                                      \
      "0 PCSS: blocker search and PCF (thesis 3.4), 1 light-space horizons over the map's front "  \
      "and back faces (docs/effects.md)")                                                          \
    X(shadow_taps, int, 49, 1, 64, "Shadow",                                                       \
      "PCF taps of variant 0 (1 = the hard shadow test, in either variant; thesis: 49, or 9 + "    \
      "cache)")                                                                                    \
    X(shadow_directions, int, 12, 1, 64, "Shadow", "directions of variant 1's horizons per pixel") \
    X(shadow_steps, int, 6, 1, 64, "Shadow", "samples along each of variant 1's directions")       \
    X(contact_shadows, bool, false, 0, 1, "Shadow",                                                \
      "screen-space contact shadows on the shadow term")                                           \
    X(contact_shadow_steps, int, 8, 1, 64, "Shadow", "samples along the contact-shadow segment")   \
    X(contact_shadow_texels, double, 6, 0, 1e3, "Shadow",                                          \
      "length of the contact-shadow segment, in texels of the RSM (rsm_size)")                     \
    X(ao, bool, true, 0, 1, "Ambient occlusion", "ambient occlusion on or off")                    \
    X(ao_variant, int, 2, 0, 2, "Ambient occlusion",                                               \
      "0 thesis (eq. 6-8), 1 Crytek/Mittring, 2 horizon (GTAO)")                                   \
    X(ao_radius, double, 0, 0, 1e9, "Ambient occlusion",                                           \
      "AO radius in scene units; 0 = 1.25% of the scene's diagonal beside the sky's visibility "   \
      "(which takes the occluders beyond it), else 5% (a bare glTF's: of the model's)")            \
    X(ao_directions, int, 8, 1, 32, "Ambient occlusion", "AO sampling directions per pixel")       \
    X(ao_steps, int, 4, 1, 32, "Ambient occlusion",                                                \
      "AO samples per direction (log-spaced, eq. 8)")                                              \
    X(ao_attenuation_a, double, 1.0, 0, 1e3, "Ambient occlusion",                                  \
      "a in D(d) = 1 + a d + b d^2, d in AO radii")                                                \
    X(ao_attenuation_b, double, 0.0, 0, 1e3, "Ambient occlusion",                                  \
      "b in D(d) = 1 + a d + b d^2, d in AO radii")                                                \
    X(sky_visibility, bool, true, 0, 1, "Ambient occlusion",                                       \
      "the sky occluded beyond the AO radius, from depth maps of the scene over the sky; with "    \
      "AO, not SSDO (docs/effects.md)")                                                            \
    X(sky_visibility_directions, int, 64, 1, 1024, "Ambient occlusion",                            \
      "directions (depth maps) of the sky visibility, over the whole sphere")                      \
    X(sky_visibility_map_size, int, 256, 16, 4096, "Ambient occlusion",                            \
      "texels per side of each sky visibility depth map")                                          \
    X(ssdo, bool, false, 0, 1, "SSDO", "SSDO replaces AO: directional sky occlusion + one bounce") \
    X(ssdo_samples, int, 16, 1, 64, "SSDO", "SSDO hemisphere samples per pixel")                   \
    X(ssdo_radius, double, 0, 0, 1e9, "SSDO", "SSDO r_max in scene units; 0 = the AO radius")      \
    X(ssdo_bounce, double, 1.0, 0, 1e3, "SSDO",                                                    \
      "SSDO one-bounce strength (the paper's user factor)")                                        \
    X(depth_peeling, bool, false, 0, 1, "SSDO",                                                    \
      "SSDO's, the contact shadows' and the bounce's occlusion tests between two depth layers")    \
    X(rsm_size, int, 1024, 16, 8192, "Indirect light",                                             \
      "the reflective shadow map, texels per side: each texel a VPL")                              \
    X(indirect, bool, true, 0, 1, "Indirect light",                                                \
      "one-bounce indirect light from the RSM on or off")                                          \
    X(indirect_method, int, 3, 0, 3, "Indirect light",                                             \
      "0 the thesis's gather: every VPL per half-resolution pixel, upsampled; 1 interleaved: "     \
      "each pixel of a k x k block gathers 1/k^2 of the RSM's texels, then a geometry-aware "      \
      "filter; 2 importance: 1 from clustered VPLs, some drawn by flux, visibility tested on a "   \
      "few drawn by their light; 3 world cache: cells in world space gather the flux's VPLs "      \
      "through a voxel grid, pixels look them up")                                                 \
    X(indirect_vpls, int, 384, 1, 1024, "Indirect light",                                          \
      "VPLs of the pattern: method 0, gathered by every pixel (the thesis's: 512); methods 1-2, "  \
      "split among a block")                                                                       \
    X(indirect_flux_vpls, int, 64, 1, 512, "Indirect light",                                       \
      "method 2: VPLs drawn by flux that each block gathers (split among it like the pattern's)")  \
    X(indirect_flux_pool, int, 2048, 1, 16384, "Indirect light",                                   \
      "methods 2-3: VPLs drawn each frame in proportion to the RSM's flux; each 8 x 8 pixels "     \
      "(method 2) or each cell (method 3) take a run of them")                                     \
    X(indirect_vpl_cluster, int, 4, 1, 16, "Indirect light",                                       \
      "methods 2-3: RSM texels per VPL, per side (the RSM clustered into a coarser map of VPLs)")  \
    X(indirect_visibility_tests, int, 6, 0, 1024, "Indirect light",                                \
      "method 2: VPLs a pixel tests for visibility, drawn by their light; 0 = every one")          \
    X(indirect_interleave, int, 4, 1, 8, "Indirect light",                                         \
      "methods 1-2: k, the block side: k^2 subsets (at most the square root of indirect_vpls)")    \
    X(indirect_filter_radius, int, 8, 1, 32, "Indirect light",                                     \
      "methods 1-2: reach in pixels of the geometry-aware filter, per axis")                       \
    X(indirect_radius, double, 0.0, 0, 2, "Indirect light",                                        \
      "VPL sampling radius in RSM uv; 0 = reach the whole map")                                    \
    X(indirect_visibility, bool, true, 0, 1, "Indirect light",                                     \
      "screen-space visibility test of each VPL")                                                  \
    X(indirect_visibility_steps, int, 6, 1, 32, "Indirect light",                                  \
      "log-spaced steps of the visibility test")                                                   \
    X(indirect_visibility_start, double, 0.1, 0.001, 0.9, "Indirect light",                        \
      "where the visibility test's log-spaced march begins, a fraction of the way to the VPL "     \
      "(nearer: longer far steps, which take open space behind an object for an occluder)")        \
    X(indirect_visibility_light, bool, true, 0, 1, "Indirect light",                               \
      "where the visibility test takes its last step for blocked, the light's depth "              \
      "(light_depth_min) may tell it open: the step's stretch seen open above the VPL's surface")  \
    X(indirect_half_res, bool, true, 0, 1, "Indirect light",                                       \
      "method 0: gather at half resolution and upsample (1), or every pixel at full (0)")          \
    X(world_voxels, int, 256, 8, 512, "World cache",                                               \
      "method 3: voxels along the scene's longest side in the occupancy grid its visibility "      \
      "test walks")                                                                                \
    X(world_cell_angle, double, 0.03, 1e-4, 1, "World cache",                                      \
      "method 3: the angle a cell spans from the camera (radians): a cell at distance d is the "   \
      "power of two nearest below d x this wide")                                                  \
    X(world_level_reuse, bool, true, 0, 1, "World cache",                                          \
      "method 3: a pixel whose own cell is absent takes the cell one level coarser or finer at "   \
      "its point, if an earlier frame gathered it, rather than making its own")                    \
    X(world_half_res, bool, false, 0, 1, "World cache",                                            \
      "method 3: cells looked up at the top-left pixel of every 2x2 block (every pixel still "     \
      "finds or makes its own), the bounce upsampled from those on a pixel's surface (a pixel "    \
      "with none is looked up alone)")                                                             \
    X(world_sky_visibility, bool, false, 0, 1, "World cache",                                      \
      "method 3: the sky's visibility beyond the AO (sky_visibility) held in the cells beside "    \
      "the bounce and looked up with it, rather than computed at each pixel and cached there "     \
      "(off: a cell keeps the value at the point the view it was made in chose; "                  \
      "docs/world-cache.md)")                                                                      \
    X(world_vpls, int, 48, 2, 1024, "World cache",                                                 \
      "method 3: VPLs a cell gathers, with their visibility, in a frame's refresh (half by flux, " \
      "half next to it)")                                                                          \
    X(world_frames, int, 16, 1, 512, "World cache",                                                \
      "method 3: frames of world_vpls a cell accumulates before it stops")                         \
    X(world_new_cell_frames, int, 8, 1, 512, "World cache",                                        \
      "method 3: frames of world_vpls a new cell gathers at once (at most world_frames), as "      \
      "every cell does each frame without the cache")                                              \
    X(world_cells_per_frame, int, 1024, 0, 1 << 24, "World cache",                                 \
      "method 3: about this many cells refreshed a frame beyond the new ones (which are always "   \
      "filled), a window that slides over the cells short of world_frames")                        \
    X(world_table_bits, int, 0, 0, 22, "World cache",                                              \
      "method 3: the hash table holds 2^bits cells; 0: sized from the image, the power of two at " \
      "or above half its pixels, 2^14 to 2^18")                                                    \
    X(world_lifetime, int, 120, 1, 1 << 24, "World cache",                                         \
      "method 3: frames a cell stays while no pixel uses it")                                      \
    X(cache, bool, true, 0, 1, "Temporal cache",                                                   \
      "the temporal cache of shadow, AO, SSDO and indirect light")                                 \
    X(cache_method, int, 0, 0, 1, "Temporal cache",                                                \
      "0 the thesis's confidence rule (eq. 4-5), 1 running mean")                                  \
    X(cache_bias, double, 0.0, 0, 1e3, "Temporal cache", "bias of the confidence rule (eq. 4)")    \
    X(cache_epsilon, double, 2.0, 0, 1e3, "Temporal cache",                                        \
      "reprojection test (eq. 3), in pixel footprints")                                            \
    X(cache_thin_geometry, bool, true, 0, 1, "Temporal cache",                                     \
      "where the nearest history texel lies behind, the reprojection also tries the 8 beside it, " \
      "so features under a pixel wide keep their history")                                         \
    X(cache_screen_edge, bool, true, 0, 1, "Temporal cache",                                       \
      "where the camera moves the screen's edges across the AO's radius, its history starts over " \
      "(what it saw beyond the edge is not what this view sees)")                                  \
    X(cache_rotations, int, 36, 1, CACHE_COUNT_MAX, "Temporal cache",                              \
      "pattern rotations until a pixel is converged")                                              \
    X(cache_rotation_deg, double, 10.0, -360, 360, "Temporal cache",                               \
      "turn of every sampling pattern a frame")                                                    \
    X(cache_scale_jitter, double, 0.1, 0, 0.9, "Temporal cache",                                   \
      "relative change of pattern size a frame")                                                   \
    X(cache_reuse_moving, bool, true, 0, 1, "Temporal cache",                                      \
      "while the camera moves, reuse a pixel whose history reprojects onto its surface and holds " \
      "one computation or more, until its resampling blur reaches the effect's budget "            \
      "(cache_blur_<effect>; the shadow's where its texels agree and the shadow map's texel at "   \
      "the pixel does not contradict them); 0: only converged pixels are reused")                  \
    X(cache_refresh, bool, true, 0, 1, "Temporal cache",                                           \
      "tiled refresh: one tile a frame computed anew")                                             \
    X(cache_cut_angle_deg, double, 45.0, 0, 180, "Temporal cache",                                 \
      "a camera turn beyond this between two frames is a cut: every history restarts (180: "       \
      "never)")                                                                                    \
    X(cache_cut_distance, double, 0.2, 0, 1e9, "Temporal cache",                                   \
      "a camera jump beyond this x the scene's diagonal between two frames is a cut")              \
    X(cache_resize, bool, true, 0, 1, "Temporal cache",                                            \
      "a resize resamples every history to the new size (1) or drops it (0)")                      \
    X(cache_temporal_slots, int, 4, 1, 4, "Temporal cache",                                        \
      "cached effects one temporal dispatch blends (4: all of a frame's in one; 1: a dispatch "    \
      "per effect, the same values)")                                                              \
    X(cache_samples, double, 0.5, 0.01, 1, "Temporal cache",                                       \
      "share of a cached effect's samples a frame takes, the cache accumulating the rest, where "  \
      "its history outlasts a moving camera (a cache_blur_ budget above 0: the AO's by "           \
      "default): the AO's directions and steps (not the horizon variant's), the shadow's "         \
      "directions (variant 1) or taps (variant 0), SSDO's samples (1: as many as uncached; a "     \
      "frame whose history restarts takes them all; docs/temporal-cache.md)")                      \
    X(cache_shadow, bool, true, 0, 1, "Temporal cache",                                            \
      "the shadow term cached (1), or computed anew every frame")                                  \
    X(cache_ao, bool, true, 0, 1, "Temporal cache", "the AO cached (1), or computed anew")         \
    X(cache_ssdo, bool, true, 0, 1, "Temporal cache", "SSDO cached (1), or computed anew")         \
    X(cache_indirect, bool, true, 0, 1, "Temporal cache",                                          \
      "the indirect light cached (1), or computed anew")                                           \
    X(cache_sky_visibility, bool, true, 0, 1, "Temporal cache",                                    \
      "the sky's visibility cached (1: computed once per surface point, reused where it "          \
      "reprojects), or computed anew")                                                             \
    X(cache_tile_shadow, int, 64, 1, 4096, "Temporal cache",                                       \
      "refresh tile size of the shadow (pixels)")                                                  \
    X(cache_tile_ao, int, 64, 1, 4096, "Temporal cache", "refresh tile size of the AO (pixels)")   \
    X(cache_tile_ssdo, int, 64, 1, 4096, "Temporal cache", "refresh tile size of SSDO (pixels)")   \
    X(cache_tile_indirect, int, 16, 1, 4096, "Temporal cache",                                     \
      "refresh tile size of the indirect light (pixels)")                                          \
    X(cache_tile_sky_visibility, int, 64, 1, 4096, "Temporal cache",                               \
      "refresh tile size of the sky's visibility (pixels)")                                        \
    X(cache_blur_shadow, double, 0.0, 0, 1e6, "Temporal cache",                                    \
      "resampling blur (pixels^2) a moving camera may leave in the shadow's history before its "   \
      "weight is cut")                                                                             \
    X(cache_blur_ao, double, 2.0, 0, 1e6, "Temporal cache",                                        \
      "the same for the AO's history (pixels^2)")                                                  \
    X(cache_blur_ssdo, double, 0.0, 0, 1e6, "Temporal cache",                                      \
      "the same for SSDO's history (pixels^2; 0: computed anew while the camera moves, since "     \
      "what SSDO sees on screen changes with the view)")                                           \
    X(cache_blur_indirect, double, 0.0, 0, 1e6, "Temporal cache",                                  \
      "the same for the indirect light's history (pixels^2; 0: computed anew while the camera "    \
      "moves; with 4, its resampled history left depth edges biased long after a stop)")           \
    X(cache_blur_sky_visibility, double, 4.0, 0, 1e6, "Temporal cache",                            \
      "the same for the sky's visibility (pixels^2): beyond it a value is computed again")

struct Settings {
#define SSGI_SETTING_MEMBER(name, type, value, lo, hi, group, meaning) type name = value;
    SSGI_SETTINGS(SSGI_SETTING_MEMBER)
#undef SSGI_SETTING_MEMBER
};

// One row of the table, for code that goes over every setting or finds one by its name.
struct SettingRow {
    const char* name;
    const char* type; // "bool", "int" or "double"
    double defaultValue, min, max;
    const char* group;
    const char* meaning;
    double (*get)(const Settings&);
    void (*set)(Settings&, double); // the value already checked
    bool flag() const { return std::string_view(type) == "bool"; }
    bool whole() const { return flag() || std::string_view(type) == "int"; }
};
std::span<const SettingRow> settingTable();

// Settings by name, as a scene file or `--set` gives them, already checked.
using SettingOverrides = std::map<std::string, double>;

// Checks `value` for setting `name`; throws InputError "<where>: ..." naming the setting and its
// range (or, for an unknown name, the known ones).
double checkSetting(const std::string& where, const std::string& name, double value);
// `settings` with each of `overrides` checked and applied.
Settings withOverrides(Settings settings, const SettingOverrides& overrides,
                       const std::string& where);
// Every setting's value by name (what a benchmark records beside its figures).
SettingOverrides settingValues(const Settings& settings);
// One setting's value by name; std::logic_error for a name the table lacks (code asking for a
// row nobody declared, such as a cached effect's cache_<effect>).
double settingValue(const Settings& settings, const std::string& name);

// The table as docs/settings.md shows it (`render --list-settings` prints it; a test checks that
// the docs hold it).
std::string settingsMarkdown();

} // namespace ssgi
