#include "renderer.h"

#include "frame_uniforms.h"

#include "passes/passes.h"
#include "passes/views.h"

#include "scene/animation.h"
#include "scene/camera.h"
#include "scene/warnings.h"
#include "shared.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtx/component_wise.hpp>
#include <limits>
#include <stdexcept>

namespace ssgi {

// A quarter of half-float range: radiance up to this is kept in its own units.
constexpr float kLargestUnscaledRadiance = 16384.0f;

const std::vector<std::string>& viewNames() {
    static const std::vector<std::string> names = [] {
        std::vector<std::string> list;
        for (const ViewDef& v : kViews)
            list.push_back(v.name);
        return list;
    }();
    return names;
}

// A view's place in kViews (views.h); InputError listing the views otherwise.
static int viewIndex(const std::string& name) {
    const ViewDef* view = findView(name);
    if (!view) {
        std::string list;
        for (const ViewDef& v : kViews)
            list += std::string(" ") + v.name;
        throw InputError("unknown view '" + name + "' (views:" + list + ")");
    }
    return int(view - kViews);
}

// The frame's largest images hold 16 bytes a pixel (world positions, the HDR image); a size
// whose image is larger than the device allows for one image, or than its memory, is refused
// before anything is made, with the figures (it was a failed vkBindImageMemory).
static void checkImageMemory(const vk::Context& ctx, uint32_t width, uint32_t height) {
    VkImageFormatProperties limits{};
    vkGetPhysicalDeviceImageFormatProperties(ctx.physicalDevice, VK_FORMAT_R32G32B32A32_SFLOAT,
                                             VK_IMAGE_TYPE_2D, VK_IMAGE_TILING_OPTIMAL,
                                             VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT |
                                                 VK_IMAGE_USAGE_SAMPLED_BIT |
                                                 VK_IMAGE_USAGE_TRANSFER_SRC_BIT,
                                             0, &limits);
    VkDeviceSize heap = 0;
    for (uint32_t h = 0; h < ctx.memoryProperties.memoryHeapCount; ++h)
        if (ctx.memoryProperties.memoryHeaps[h].flags & VK_MEMORY_HEAP_DEVICE_LOCAL_BIT)
            heap = std::max(heap, ctx.memoryProperties.memoryHeaps[h].size);
    const VkDeviceSize image = VkDeviceSize(width) * height * 16;
    const VkDeviceSize allowed = std::min(limits.maxResourceSize, heap);
    if (image <= allowed) return;
    throw InputError("image size " + std::to_string(width) + "x" + std::to_string(height) +
                     " needs " + std::to_string(image >> 20) +
                     " MiB for each of the frame's 16-byte-per-pixel images, and there are "
                     "several; this device allows " +
                     std::to_string(limits.maxResourceSize >> 20) + " MiB for one image and has " +
                     std::to_string(heap >> 20) + " MiB of memory: choose a smaller --size");
}

Renderer::Renderer(vk::Context& ctx, const Scene& scene, const RenderOptions& options)
    : Renderer(ctx, scene, options, nullptr) {}

Renderer::Renderer(vk::Context& ctx, const Scene& scene, const RenderOptions& options,
                   Renderer& previous)
    : Renderer(ctx, scene, options, &previous) {}

Renderer::Renderer(vk::Context& ctx, const Scene& scene, const RenderOptions& options,
                   Renderer* previous)
    : ctx_(ctx), scene_(scene), builtSettings_(scene.settings), light_(scene.light),
      patternStart_(options.patternStart), seals_(scene) {
    const uint32_t limit = ctx.properties.limits.maxImageDimension2D;
    // The screen images hold the output and the guard band on each side (PassSetup::output).
    const uint32_t band = uint32_t(scene.settings.guard_band);
    const VkExtent2D rendered{options.width + 2 * band, options.height + 2 * band};
    if (options.width == 0 || options.height == 0 || rendered.width > limit ||
        rendered.height > limit)
        throw InputError(
            "image size " + std::to_string(options.width) + "x" + std::to_string(options.height) +
            (band ? " with a guard band of " + std::to_string(band) + " pixels" : "") +
            " is outside 1.." + std::to_string(limit) + " (this device's largest 2D image)");
    checkImageMemory(ctx, rendered.width, rendered.height);
    const int view = viewIndex(options.view);
    const uint32_t rsmSize = uint32_t(scene.settings.rsm_size);
    for (const auto& [name, side] : {std::pair{"rsm_size", rsmSize},
                                     {"shadow_map_size", uint32_t(scene.settings.shadow_map_size)}})
        if (side == 0 || side > limit)
            throw InputError(std::string(name) + " " + std::to_string(side) + " is outside 1.." +
                             std::to_string(limit));

    // A failure past this point (out of device memory) gives back what was made before it.
    try {
        if (previous) { // its frames' work done, its scene's copy and pipelines taken; its
                        // graph gives up its drawn images below (takeDrawn), then goes
            vkDeviceWaitIdle(ctx.device);
            sceneGpu_ = std::move(previous->sceneGpu_);
            pipelines_ = std::move(previous->pipelines_);
            sceneGpu_->rebind(scene);
        } else {
            sceneGpu_ = std::make_unique<SceneGpu>(ctx, scene);
            pipelines_ = std::make_unique<vk::PipelineStore>(ctx);
        }
        transforms_ = instanceTransformsAt(scene, kBeforeFirstKey);
        origin_ = gpuOrigin(scene.bounds);
        uploadTransforms();
        graph_ = std::make_unique<graph::FrameGraph>(ctx);
        graph_->setRecordingLog(options.logRecording);
        build_ =
            std::make_unique<FrameBuild>(ctx, *graph_, *sceneGpu_, *pipelines_, scene, rendered,
                                         band, VkExtent2D{rsmSize, rsmSize}, origin_);
        view_ = view;
        addFramePasses(*build_);
        for (const std::string& name : options.keep) {
            if (name == "*") graph_->keepAll();
            if (const graph::ImageRef ref = imageNamed(name); ref.valid()) graph_->keep(ref);
        }
        graph_->allocateTransients();
        if (previous) {
            takeDrawn(*previous);
            previous->release();
        }
    } catch (...) {
        if (previous) previous->release();
        release();
        throw;
    }
}

Renderer::~Renderer() {
    release();
}

void Renderer::release() {
    vkDeviceWaitIdle(ctx_.device);
    build_.reset();
    graph_.reset();
    pipelines_.reset();
}

std::vector<glm::mat4> Renderer::gpuTransforms() const {
    std::vector<glm::mat4> onGpu = transforms_;
    for (glm::mat4& m : onGpu)
        m = moved(m, origin_);
    return onGpu;
}

void Renderer::uploadTransforms() {
    sceneGpu_->setTransforms(gpuTransforms());
}

void Renderer::updateUniforms(const Camera& worldCamera) {
    const VkExtent2D size = build_->size, output = build_->output().extent;
    const float aspect = float(output.width) / float(output.height);
    // The camera, light and bounds as the GPU sees them (see gpuOrigin).
    Camera camera = worldCamera;
    camera.position = moved(camera.position, origin_);
    SpotLight l = light_;
    l.position = moved(l.position, origin_);
    const Aabb bounds{moved(scene_.bounds.min, origin_), moved(scene_.bounds.max, origin_)};
    const LightFrustum light = lightFrustum(l, bounds);
    shader::FrameUniforms u{};
    u.view = viewMatrix(camera);
    // The camera's frustum fills the output; the guard band widens it by as many pixels on
    // each side: x and y shrink in clip space by output / rendered, so a pixel of the output
    // sees the same ray it would without a band.
    const glm::vec3 band(float(output.width) / float(size.width),
                         float(output.height) / float(size.height), 1.0f);
    u.projection = glm::scale(glm::mat4(1.0f), band) * projectionMatrix(camera, aspect);
    u.viewProjection = u.projection * u.view;
    u.inverseViewProjection = glm::inverse(u.viewProjection);
    u.previousViewProjection = frameIndex_ == 0 ? u.viewProjection : previousViewProjection_;
    reprojectedInto_ = u.previousViewProjection;
    u.cameraMoved = u.viewProjection != u.previousViewProjection ? 1.0f : 0.0f;
    u.pixelToWorld = pixelToWorld(u.view, u.projection, size);
    u.previousPixelToWorld = frameIndex_ == 0 ? u.pixelToWorld : previousPixelToWorld_;
    const bool still =
        frameIndex_ > 0 && u.viewProjection == previousViewProjection_ && moved_.empty();
    stillFrames_ = still ? stillFrames_ + 1 : 0;
    if (!still) gbufferSidesHeld_ = 0;
    u.lightViewProjection = light.viewProjection;
    u.inverseLightViewProjection = glm::inverse(light.viewProjection);
    u.lightPixelToWorld = pixelToWorld(light.view, light.projection, build_->rsmSize);
    u.cameraPosition = glm::vec4(camera.position, 1.0f);
    u.lightPosition = glm::vec4(l.position, l.radius);
    u.lightDirection = glm::vec4(glm::normalize(l.direction), std::cos(l.outerConeAngle));
    // The brightest radiance to expect: the sky's, and the light's on a white surface a
    // twentieth of the scene away. Past a quarter of half-float range the lights are scaled down
    // (by a power of two, which loses no precision) and the composite scales its result back up.
    const float diagonal = glm::length(scene_.bounds.size());
    const glm::vec3 emitted = l.color * l.intensity;
    const float nearby = 0.05f * diagonal;
    const float peak = std::max({glm::compMax(scene_.sky.zenith), glm::compMax(scene_.sky.horizon),
                                 glm::compMax(scene_.sky.ground),
                                 glm::compMax(emitted) / (glm::pi<float>() * nearby * nearby)});
    const float scale =
        peak > kLargestUnscaledRadiance ? std::exp2(std::ceil(std::log2(peak / 1024.0f))) : 1.0f;
    u.radianceScale = glm::vec4(scale, 0.0f, 0.0f, 0.0f);
    // A sealed light (updateSeal) lights nothing the camera sees: nothing it emits is drawn.
    u.lightColor = glm::vec4(seal_ ? glm::vec3(0.0f) : emitted / scale, std::cos(l.innerConeAngle));
    u.lightFrustum =
        glm::vec4(light.znear, light.zfar, light.tanHalfFov, float(build_->rsmSize.width));
    u.skyZenith = glm::vec4(scene_.sky.zenith / scale, 0.0f);
    u.skyHorizon = glm::vec4(scene_.sky.horizon / scale, 0.0f);
    u.skyGround = glm::vec4(scene_.sky.ground / scale, 0.0f);
    u.viewport = glm::vec4(size.width, size.height, 1.0f / size.width, 1.0f / size.height);
    u.exposure = float(scene_.settings.exposure);
    u.patternFrame = float(patternFrame());
    u.sceneDiagonal = glm::length(scene_.bounds.size());
    for (size_t i = 0; i < moved_.size(); ++i) {
        u.movedBoxes[2 * i] = glm::vec4(moved(moved_[i].min, origin_), 0.0f);
        u.movedBoxes[2 * i + 1] = glm::vec4(moved(moved_[i].max, origin_), 0.0f);
    }
    u.motion = glm::vec4(float(moved_.size()), 0.0f, 0.0f, 0.0f);
    if (scene_.settings.indirect && scene_.settings.indirect_method == 3) {
        // Placed again on the frames the grid is drawn again (decideFrame: drawVoxels).
        if (voxelsStale_)
            worldGrid_ =
                placeWorldGrid(boundsInFrustum(scene_, gpuTransforms(), light.viewProjection),
                               int(scene_.settings.world_voxels));
        u.worldGridOrigin = glm::vec4(worldGrid_.origin, worldGrid_.voxel);
        u.worldGridSize = glm::ivec4(worldGrid_.size, int(scene_.settings.world_voxels));
    }
    std::memcpy(build_->frameUniforms.mapped, &u, sizeof(u));
    previousViewProjection_ = u.viewProjection;
    previousPixelToWorld_ = u.pixelToWorld;
    lastLightColor_ = glm::vec3(u.lightColor);
}

// A cut: asked for (cut(), a path key), or a turn or jump between two frames beyond the
// cache_cut_* settings. No history survives it: reprojection across a cut would keep values
// that only look like the same surface (docs/temporal-cache.md measures how many and how wrong).
bool Renderer::startsAfresh(const Camera& camera) const {
    if (cutRequested_) return true;
    if (frameIndex_ == 0) return false;
    const glm::vec3 before = previousCamera_.orientation * glm::vec3(0.0f, 0.0f, -1.0f);
    const glm::vec3 now = camera.orientation * glm::vec3(0.0f, 0.0f, -1.0f);
    const float turn = std::acos(std::clamp(glm::dot(before, now), -1.0f, 1.0f));
    const float jump = glm::distance(previousCamera_.position, camera.position);
    return turn > glm::radians(float(scene_.settings.cache_cut_angle_deg)) ||
           jump > float(scene_.settings.cache_cut_distance) * glm::length(scene_.bounds.size());
}

void Renderer::renderFrame(const Camera& camera) {
    if (startsAfresh(camera)) {
        graph_->resetHistory();
        stillFrames_ = 0; // nor is the screen settled: every pixel is computed again
        gbufferSidesHeld_ = 0;
        ++cuts_;
    }
    cutRequested_ = false;
    previousCamera_ = camera;
    updateSeal(camera);
    // Images taken from an unsealed renderer (takeDrawn) do not hold a sealed light's.
    if (frameIndex_ == 0 && tookDrawn_ && seal_) rsmStale_ = skyMapsStale_ = voxelsStale_ = true;
    updateUniforms(camera);
    lastFrame_ = decideFrame();
    lastSubmission_ =
        ctx_.submitAndWait([&](VkCommandBuffer cmd) { graph_->record(cmd, lastFrame_); });
    graph_->endFrame();
    if (lastFrame_.drawGBuffer) gbufferSidesHeld_ = std::min(gbufferSidesHeld_ + 1, 2u);
    rsmStale_ = false;
    skyMapsStale_ = false;
    voxelsStale_ = false;
    lightMoved_ = false;
    worldCacheEmpty_ = false;
    moved_.clear();
    ++frameIndex_;
}

void Renderer::updateSeal(const Camera& camera) {
    if (!sealStale_ && camera.position == sealCamera_.position && camera.yfov == sealCamera_.yfov &&
        camera.znear == sealCamera_.znear)
        return;
    // The rays the frame casts start on the near plane of its frustum, which the guard band
    // widens (updateUniforms).
    const VkExtent2D size = build_->size, output = build_->output().extent;
    Camera widened = camera;
    widened.yfov =
        2.0f * std::atan(std::tan(0.5f * camera.yfov) * float(size.height) / float(output.height));
    std::optional<Seal> seal =
        seals_.find(light_, widened, float(size.width) / float(size.height), transforms_);
    sealStale_ = false;
    sealCamera_ = camera;
    if (seal.has_value() != seal_.has_value() && frameIndex_ > 0) lightChanged();
    seal_ = std::move(seal);
    if (seal_ && !sealWarned_) {
        warn(sealWarning(*seal_));
        sealWarned_ = true;
    }
}

FrameState Renderer::decideFrame() {
    const Settings& settings = scene_.settings;
    FrameState f;
    // Every frame turns the sampling patterns by a fixed angle and varies their size a little
    // (golden-ratio sequence), so successive frames take different samples (thesis 3.1.2;
    // docs/temporal-cache.md), and moves each sample within its radial stratum (another
    // low-discrepancy sequence, so that offset and scale do not repeat together).
    const float turn = glm::radians(float(settings.cache_rotation_deg));
    const float jitter = float(settings.cache_scale_jitter);
    const float frame = float(patternFrame());
    f.patternRotation = std::fmod(frame * turn, 2.0f * glm::pi<float>());
    f.patternScale = 1.0f + jitter * (2.0f * std::fmod(frame * 0.618034f, 1.0f) - 1.0f);
    f.patternOffset = std::fmod(0.5f + frame * 0.7548777f, 1.0f);
    f.patternFrame = patternFrame();
    // Without the cache nothing persists from frame to frame: the RSM is drawn every frame.
    f.drawRsm = rsmStale_ || !settings.cache;
    f.drawSkyMaps = skyMapsStale_;
    f.lightMoved = lightMoved_;
    f.objectsMoved = !moved_.empty();
    f.drawVoxels = voxelsStale_;
    f.clearWorldCache = worldCacheEmpty_ || !settings.cache;
    f.drawGBuffer = !settings.cache || gbufferSidesHeld_ < 2;
    f.settled = stillFrames_ >= uint32_t(settings.cache_rotations);
    f.view = view_;
    f.effects = nextCacheFrames(*graph_, build_->caches);
    // A settled frame computes no effect. Its histories are converged and hold no resampling
    // blur, and on a still camera a refreshed tile would be computed only to be left out of
    // them (temporal.comp keeps such a history as it is: the refresh pulls back resampling
    // blur, and there is none). The first settled frame copies each history to this frame's
    // side of its pair; then both sides hold it, and nothing writes either.
    f.copyHistories = f.settled && !lastFrame_.settled;
    if (f.settled)
        for (CachedEffectFrame& effect : f.effects)
            effect.refreshTile = -1;
    return f;
}

FrameProfile Renderer::lastFrameProfile() const {
    return {frameIndex_ - 1, graph_->timings(), lastSubmission_.milliseconds,
            lastSubmission_.startUs};
}

void Renderer::setView(const std::string& view) {
    view_ = viewIndex(view);
}

void Renderer::setTime(float seconds) {
    for (const CameraKey& key : scene_.cameraPath.keys)
        if (key.cut && time_ < key.time && key.time <= seconds) cutRequested_ = true;
    time_ = seconds;
    const std::vector<glm::mat4> next = instanceTransformsAt(scene_, seconds);
    bool any = false;
    for (size_t i = 0; i < next.size(); ++i) {
        if (next[i] == transforms_[i]) continue;
        Aabb box = instanceBounds(scene_, i, transforms_[i]);
        const Aabb now = instanceBounds(scene_, i, next[i]);
        box.extend(now.min);
        box.extend(now.max);
        // At most four boxes reach the shaders: beyond that the last one holds the rest.
        if (moved_.size() < 4) {
            moved_.push_back(box);
        } else {
            moved_.back().extend(box.min);
            moved_.back().extend(box.max);
        }
        any = true;
    }
    if (!any) return;
    transforms_ = next;
    uploadTransforms();
    sealStale_ = true;
    rsmStale_ = true;
    skyMapsStale_ = true;
    voxelsStale_ = true;
    for (const EffectCache& cache : build_->caches.effects)
        if (cache.effect.motionTest == MOTION_RESTART_ALL) restartCache(*graph_, cache);
}

void Renderer::setLight(const SpotLight& light) {
    light_ = light;
    sealStale_ = true;
    lightChanged();
}

void Renderer::lightChanged() {
    rsmStale_ = true;
    lightMoved_ = true;
    voxelsStale_ = true; // the grid lies within the light's frustum (world_grid.h)
    stillFrames_ = 0;
    for (const EffectCache& cache : build_->caches.effects)
        if (cache.effect.lightDependent) restartCache(*graph_, cache);
}

} // namespace ssgi
