#include "renderer.h"

#include "scene/animation.h"
#include "scene/camera.h"
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

// Where the GPU's coordinates have their origin. A float holds about 7 digits, so a scene 1e5
// units from the origin keeps about 1 cm of precision in its G-buffer positions, reprojection
// tests and shadow lookups, and renders visibly wrong. Everything that reaches the GPU is
// therefore moved, in double precision on the CPU, by minus the centre of the scene's bounds:
// geometry (through the instance transforms), camera, light, light frustum and moved boxes; the
// previous frame's matrices were made the same way. A scene near the origin (its centre within
// 16 diagonals) keeps the origin where it is, so that its numbers do not change at all.
static glm::dvec3 gpuOrigin(const Aabb& bounds) {
    const glm::dvec3 centre = (glm::dvec3(bounds.min) + glm::dvec3(bounds.max)) * 0.5;
    const double diagonal = glm::length(glm::dvec3(bounds.max) - glm::dvec3(bounds.min));
    // A float itself, so that the GPU's float arithmetic (vertex minus origin, in the instance
    // transform) gives the same exact differences as the CPU's double.
    return glm::compMax(glm::abs(centre)) <= 16.0 * diagonal ? glm::dvec3(0.0)
                                                             : glm::dvec3(glm::vec3(centre));
}

static glm::vec3 moved(const glm::vec3& point, const glm::dvec3& origin) {
    return glm::vec3(glm::dvec3(point) - origin);
}

// translate(-origin) * m, in double precision.
static glm::mat4 moved(const glm::mat4& m, const glm::dvec3& origin) {
    glm::dmat4 d(m);
    for (int column = 0; column < 4; ++column)
        d[column] -= glm::dvec4(origin * d[column].w, 0.0);
    return glm::mat4(d);
}

// FrameUniforms::pixelToWorld: for the pixel centre p (in pixels of a `size` image) and the view
// depth d there, M (p.x d, p.y d, d, 1) is the world position. The view-space ray through p,
// scaled to reach one unit along the view axis, is affine in p for a perspective projection;
// its three coefficients are found by unprojecting three pixels, in double precision, and
// turned into the world by the view's rotation; the fourth column is the camera's position.
static glm::mat4 pixelToWorld(const glm::mat4& view, const glm::mat4& projection, VkExtent2D size) {
    const glm::dmat4 inverseProjection = glm::inverse(glm::dmat4(projection));
    auto rayAt = [&](double x, double y) { // in view space, at view depth 1
        const glm::dvec4 ndc(2.0 * x / size.width - 1.0, 2.0 * y / size.height - 1.0, 0.5, 1.0);
        const glm::dvec4 q = inverseProjection * ndc;
        return glm::dvec3(q) / -q.z;
    };
    const glm::dvec3 origin = rayAt(0.0, 0.0);
    const glm::dmat4 toWorld = glm::inverse(glm::dmat4(view));
    const glm::dmat3 rotation(toWorld);
    glm::dmat4 m(1.0);
    m[0] = glm::dvec4(rotation * (rayAt(1.0, 0.0) - origin), 0.0);
    m[1] = glm::dvec4(rotation * (rayAt(0.0, 1.0) - origin), 0.0);
    m[2] = glm::dvec4(rotation * origin, 0.0);
    m[3] = toWorld[3];
    return glm::mat4(m);
}

const std::vector<std::string>& viewNames() {
    // Order matches the VIEW_* values in shared.h.
    static const std::vector<std::string> names = {
        "final",  "albedo", "normal",   "depth", "direct",  "rsm-flux", "rsm-normal",
        "shadow", "ao",     "indirect", "ssdo",  "contact", "peel",     "sky-visibility"};
    return names;
}

// The VIEW_* value of a view's name; InputError listing the views otherwise.
static int viewIndex(const std::string& name) {
    const auto& views = viewNames();
    auto view = std::find(views.begin(), views.end(), name);
    if (view == views.end()) {
        std::string list;
        for (const auto& v : views)
            list += " " + v;
        throw InputError("unknown view '" + name + "' (views:" + list + ")");
    }
    return int(view - views.begin());
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
    : ctx_(ctx), scene_(scene), light_(scene.light), patternStart_(options.patternStart) {
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
    const uint32_t rsmSize = uint32_t(scene.settings.shadow_map_size);
    if (rsmSize == 0 || rsmSize > limit)
        throw InputError("shadow_map_size " + std::to_string(rsmSize) + " is outside 1.." +
                         std::to_string(limit));

    // A failure past this point (out of device memory) gives back what was made before it.
    try {
        sceneGpu_ = std::make_unique<SceneGpu>(ctx, scene);
        transforms_ = instanceTransformsAt(scene, std::numeric_limits<float>::lowest());
        origin_ = gpuOrigin(scene.bounds);
        uploadTransforms();
        graph_ = std::make_unique<graph::FrameGraph>(ctx);
        setup_.reset(new PassSetup{ctx, *graph_, *sceneGpu_, scene});
        setup_->gpuOrigin = origin_;
        setup_->frameUniforms = vk::createBuffer(ctx, sizeof(shader::FrameUniforms),
                                                 VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT, true);
        setup_->nearestSampler =
            vk::createSampler(ctx, VK_FILTER_NEAREST, VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE);
        setup_->linearSampler =
            vk::createSampler(ctx, VK_FILTER_LINEAR, VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE);
        setup_->size = rendered;
        setup_->guardBand = band;
        setup_->rsmSize = {rsmSize, rsmSize};

        setup_->view = view;
        addFramePasses(*setup_);
        for (const std::string& name : options.keep) {
            if (name == "*") graph_->keepAll();
            if (const graph::ImageRef ref = imageNamed(name); ref.valid()) graph_->keep(ref);
        }
        graph_->allocateTransients();
    } catch (...) {
        release();
        throw;
    }
}

Renderer::~Renderer() {
    release();
}

void Renderer::release() {
    vkDeviceWaitIdle(ctx_.device);
    graph_.reset();
    if (!setup_) return;
    for (vk::Pipeline& p : setup_->pipelines)
        vk::destroyPipeline(ctx_, p);
    for (vk::Buffer& b : setup_->buffers)
        vk::destroyBuffer(ctx_, b);
    vk::destroyBuffer(ctx_, setup_->frameUniforms);
    vkDestroySampler(ctx_.device, setup_->nearestSampler, nullptr);
    vkDestroySampler(ctx_.device, setup_->linearSampler, nullptr);
}

void Renderer::uploadTransforms() {
    std::vector<glm::mat4> onGpu = transforms_;
    for (glm::mat4& m : onGpu)
        m = moved(m, origin_);
    sceneGpu_->setTransforms(onGpu);
}

void Renderer::updateUniforms(const Camera& worldCamera) {
    const VkExtent2D size = setup_->size, output = setup_->output().extent;
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
    u.pixelToWorld = pixelToWorld(u.view, u.projection, size);
    u.previousPixelToWorld = frameIndex_ == 0 ? u.pixelToWorld : previousPixelToWorld_;
    stillFrames_ = frameIndex_ > 0 && u.viewProjection == previousViewProjection_ && moved_.empty()
                       ? stillFrames_ + 1
                       : 0;
    setup_->settled = stillFrames_ >= uint32_t(scene_.settings.cache_rotations);
    setup_->cameraStill = stillFrames_ > 0;
    u.lightViewProjection = light.viewProjection;
    u.inverseLightViewProjection = glm::inverse(light.viewProjection);
    u.lightPixelToWorld = pixelToWorld(light.view, light.projection, setup_->rsmSize);
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
    u.lightColor = glm::vec4(emitted / scale, std::cos(l.innerConeAngle));
    u.lightFrustum =
        glm::vec4(light.znear, light.zfar, light.tanHalfFov, float(setup_->rsmSize.width));
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
    std::memcpy(setup_->frameUniforms.mapped, &u, sizeof(u));
    previousViewProjection_ = u.viewProjection;
    previousPixelToWorld_ = u.pixelToWorld;
    lastLightColor_ = glm::vec3(u.lightColor);
}

// A cut: asked for (cut(), a path key), or a turn or jump between two frames beyond the
// cache_cut_* settings. No history survives it: reprojection across a cut would keep values
// that only look like the same surface (issue 20: 26% of the pixels kept theirs, at 11x a fresh
// start's error there).
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
        ++cuts_;
    }
    cutRequested_ = false;
    previousCamera_ = camera;
    // Every frame turns the sampling patterns by a fixed angle and varies their size a little
    // (golden-ratio sequence), so successive frames take different samples (thesis 3.1.2;
    // docs/temporal-cache.md).
    const float turn = glm::radians(float(scene_.settings.cache_rotation_deg));
    const float jitter = float(scene_.settings.cache_scale_jitter);
    const float frame = float(patternFrame());
    setup_->patternRotation = std::fmod(frame * turn, 2.0f * glm::pi<float>());
    setup_->patternScale = 1.0f + jitter * (2.0f * std::fmod(frame * 0.618034f, 1.0f) - 1.0f);
    // And moves each sample within its radial stratum (another low-discrepancy sequence, so
    // that offset and scale do not repeat together).
    setup_->patternOffset = std::fmod(0.5f + frame * 0.7548777f, 1.0f);
    for (EffectCache& cache : setup_->caches)
        cache.refreshTile =
            cache.refresh && graph_->hasHistory(cache.value) ? int(cache.refresh->next()) : -1;
    updateUniforms(camera);
    lastSubmission_ = ctx_.submitAndWait([&](VkCommandBuffer cmd) { graph_->record(cmd); });
    graph_->endFrame();
    setup_->rsmStale = false;
    setup_->skyMapsStale = false;
    moved_.clear();
    ++frameIndex_;
}

void Renderer::continueFrom(Renderer& previous) {
    if (&previous.scene_ != &scene_ || frameIndex_ != 0)
        throw std::logic_error("continueFrom: a new renderer of the same scene only");
    light_ = previous.light_;
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
    if (scene_.settings.cache_resize && frameIndex_ > 0) carryCaches(*previous.setup_, *setup_);
}

FrameProfile Renderer::lastFrameProfile() const {
    return {frameIndex_ - 1, graph_->timings(), lastSubmission_.milliseconds,
            lastSubmission_.startUs};
}

void Renderer::setView(const std::string& view) {
    setup_->view = viewIndex(view);
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
    setup_->rsmStale = true;
    setup_->skyMapsStale = true;
    for (EffectCache& cache : setup_->caches)
        if (cache.motionTest == MOTION_RESTART_ALL) {
            restartCache(*graph_, cache);
        }
}

void Renderer::setLight(const SpotLight& light) {
    light_ = light;
    setup_->rsmStale = true;
    stillFrames_ = 0;
    for (EffectCache& cache : setup_->caches)
        if (cache.lightDependent) {
            restartCache(*graph_, cache);
        }
}

} // namespace ssgi
