// What a new renderer takes over from the one before it: a resize's (continueFrom: the camera,
// light, objects, pattern sequence and, resampled, the cached effects' histories) and a change of
// settings' (the taking constructor's takeDrawn: the images drawn only once, where the change
// leaves them as they are; its scene on the device and pipelines are taken in the constructor).
#include "renderer.h"

#include "cache/cache.h"

#include <stdexcept>

namespace ssgi {

void Renderer::continueFrom(Renderer& previous) {
    if (&previous.scene_ != &scene_ || frameIndex_ != 0)
        throw std::logic_error("continueFrom: a new renderer of the same scene only");
    light_ = previous.light_;
    seal_ = previous.seal_;
    sealWarned_ = previous.sealWarned_;
    time_ = previous.time_;
    transforms_ = previous.transforms_;
    moved_ = previous.moved_;
    uploadTransforms();
    previousViewProjection_ = previous.previousViewProjection_;
    previousPixelToWorld_ = previous.previousPixelToWorld_;
    previousCamera_ = previous.previousCamera_;
    cutRequested_ = previous.cutRequested_;
    cuts_ = previous.cuts_;
    frameIndex_ = previous.frameIndex_;
    patternStart_ = previous.patternStart_;
    if (scene_.settings.cache_resize && frameIndex_ > 0)
        carryCaches(*previous.graph_, previous.build_->caches, previous.build_->size, *graph_,
                    build_->caches);
}

// The settings that shape the images the frame draws only once (see takeDrawn); the others
// change the passes that read them. A setting missing here that shapes one would keep a stale
// image: Python's test_session checks every setting against a renderer made anew.
static constexpr const char* kDrawnSettings[] = {"rsm_size",
                                                 "shadow_map_size",
                                                 "sky_visibility_directions",
                                                 "sky_visibility_map_size",
                                                 "world_voxels",
                                                 "indirect_vpl_cluster",
                                                 "indirect_flux_pool",
                                                 "indirect_flux_vpls",
                                                 "cache",
                                                 "ground_plane",
                                                 "guard_band"};

void Renderer::takeDrawn(Renderer& previous) {
    // Drawn for the light and the objects where this renderer has them, unsealed (a sealed light
    // draws no flux), and not to be drawn again at the old renderer's next frame.
    if (previous.seal_ || previous.light_ != light_ || previous.transforms_ != transforms_) return;
    for (const char* name : kDrawnSettings)
        if (settingValue(previous.builtSettings_, name) != settingValue(builtSettings_, name))
            return;
    // Each group of images with the flag that has the frame draw them; a group taken whole, or
    // drawn anew.
    const struct {
        bool Renderer::*stale;
        std::vector<std::string> images;
    } groups[] = {{&Renderer::rsmStale_,
                   {"rsm.vpls", "rsm.depth", "shadow_map.depth", "shadow_map_back.depth",
                    "light_depth_min", "indirect.vpl_position", "indirect.vpl_normal",
                    "indirect.vpl_flux", "indirect.flux_pyramid"}},
                  {&Renderer::skyMapsStale_, {"sky.maps"}},
                  {&Renderer::voxelsStale_,
                   {"world.voxels", "world.voxel_distance", "world.voxel_distance_xy"}}};
    for (const auto& group : groups) {
        if (previous.*group.stale) continue;
        bool whole = true; // an image neither frame has leaves the group whole
        for (const std::string& name : group.images)
            if ((graph_->find(name).valid() || previous.graph_->find(name).valid()) &&
                !graph_->adopt(name, *previous.graph_))
                whole = false;
        if (!whole) continue;
        this->*group.stale = false;
        tookDrawn_ = true;
    }
    if (!voxelsStale_) worldGrid_ = previous.worldGrid_;
}

} // namespace ssgi
