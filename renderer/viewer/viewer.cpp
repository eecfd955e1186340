#include "viewer/viewer.h"

#include "image_io.h"
#include "scene/camera.h"
#include "viewer/debug_views.h"
#include "viewer/gui.h"
#include "viewer/presenter.h"
#include "viewer/swapchain.h"
#include "viewer/window.h"

#include <GLFW/glfw3.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace ssgi::viewer {

namespace {

bool sameExtent(VkExtent2D a, VkExtent2D b) {
    return a.width == b.width && a.height == b.height;
}

void copyText(char* to, size_t capacity, const std::string& from) {
    std::snprintf(to, capacity, "%s", from.c_str());
}

} // namespace

Viewer::Viewer(const ViewerOptions& options) : options_(options) {
    // Bad input first: a missing scene is reported before any window opens.
    scene_ = cli::loadSceneWithSettings(options.common);
    const auto& views = viewNames();
    auto view = std::find(views.begin(), views.end(), options.view);
    if (view == views.end()) throw InputError("--view: unknown view '" + options.view + "'");
    panel_.view = int(view - views.begin());
    if (!options.cacheView.empty()) {
        const auto& cacheList = cacheViews();
        auto it = std::find_if(cacheList.begin(), cacheList.end(),
                               [&](const CacheViewInfo& v) { return options.cacheView == v.key; });
        if (it == cacheList.end())
            throw InputError("--cache-view: unknown view '" + options.cacheView +
                             "' (confidence, disocclusion, converged, refreshed-tile)");
        panel_.cacheView = int(it - cacheList.begin());
    }

    window_ = std::make_unique<Window>(options.common.width, options.common.height, "ssgi viewer");
    vk::ContextOptions contextOptions{options.common.validation, options.common.device};
    contextOptions.instanceExtensions = Window::requiredInstanceExtensions();
    contextOptions.createSurface = [this](VkInstance instance) {
        return window_->createSurface(instance);
    };
    ctx_ = std::make_unique<vk::Context>(contextOptions);
    window_->pollEvents();
    swapchain_ = std::make_unique<Swapchain>(*ctx_, window_->framebufferSize());
    gui_ = std::make_unique<Gui>(*ctx_, window_->handle(), *swapchain_);
    presenter_ = std::make_unique<Presenter>(*ctx_, *swapchain_, *gui_);
    panel_.device = ctx_->properties.deviceName;
    loadScene("");
    panel_.playPath = options.playPath && panel_.pathLength > 0.0f;
    if (!options.recordInto.empty()) {
        recorder_.interval = 0.0f; // a scripted run records every frame
        recorder_.start();
    }
}

Viewer::~Viewer() {
    renderer_.reset();
    presenter_.reset();
    gui_.reset();
    swapchain_.reset();
}

// Loads `path` (empty: the scene already loaded from the command line) and starts over with it.
void Viewer::loadScene(const std::string& path) {
    if (!path.empty()) {
        Scene next = ssgi::loadScene(path); // throws before anything is torn down
        renderer_.reset();
        scene_ = std::move(next);
    }
    panel_.sceneFile = scene_.sourcePath;
    copyText(panel_.scenePath, sizeof panel_.scenePath, scene_.sourcePath);
    copyText(panel_.savePathTo, sizeof panel_.savePathTo, scene_.sourcePath);
    panel_.settings = scene_.settings;
    panel_.light = scene_.light;
    panel_.pathLength = pathDuration(scene_.cameraPath);
    panel_.pathTime = 0.0f;
    panel_.playPath = false;
    const float diagonal = glm::length(scene_.bounds.size());
    panel_.cameraSpeed = 0.25f * (diagonal > 0.0f ? diagonal : 1.0f);
    fly_.reset(scene_.cameraPath.empty() ? scene_.camera : scene_.cameraPath.keys.front().camera,
               panel_.cameraSpeed);
    rebuildRenderer();
}

VkRect2D Viewer::sceneRect() const {
    const VkExtent2D window = swapchain_->extent();
    const uint32_t panel = showPanel_ ? std::min(options_.panelWidth, window.width / 2) : 0;
    return {{int32_t(panel), 0}, {std::max(1u, window.width - panel), std::max(1u, window.height)}};
}

void Viewer::rebuildRenderer(Rebuild why) {
    // A resize keeps the caches (resampled to the new size); anything else starts them over.
    std::unique_ptr<Renderer> previous = why != Rebuild::Anew ? std::move(renderer_) : nullptr;
    renderer_.reset();
    const VkRect2D rect = sceneRect();
    renderSize_ = {std::max(1u, uint32_t(std::lround(rect.extent.width * options_.renderScale))),
                   std::max(1u, uint32_t(std::lround(rect.extent.height * options_.renderScale)))};
    scene_.light = panel_.light; // the renderer starts from the scene's light
    const RenderOptions options{renderSize_.width, renderSize_.height,
                                viewNames()[size_t(panel_.view)]};
    if (why == Rebuild::Settings && previous && !previous->emptied()) {
        renderer_ = std::make_unique<Renderer>(*ctx_, scene_, options, *previous);
    } else {
        renderer_ = std::make_unique<Renderer>(*ctx_, scene_, options);
        if (why == Rebuild::Resized && previous) renderer_->continueFrom(*previous);
    }
    previous.reset();
    panel_.cachedEffects = renderer_->cachedEffects();
    panel_.cacheAvailable = !panel_.cachedEffects.empty();
    auto effect =
        std::find(panel_.cachedEffects.begin(), panel_.cachedEffects.end(), options_.cacheEffect);
    if (effect != panel_.cachedEffects.end())
        panel_.cacheEffect = int(effect - panel_.cachedEffects.begin());
    panel_.history.clear();
    rebuiltThisFrame_ = true;
}

Camera Viewer::nextCamera(float seconds) {
    const bool scripted = options_.frames > 0;
    if (panel_.pathLength > 0.0f && panel_.playPath) {
        if (scripted) {
            const float step = options_.pathStep > 0.0f
                                   ? options_.pathStep
                                   : panel_.pathLength / float(std::max(1u, options_.frames - 1));
            panel_.pathTime = std::min(float(frame_) * step, panel_.pathLength);
        } else if (frame_ > 0) {
            panel_.pathTime = std::fmod(panel_.pathTime + seconds, panel_.pathLength);
        }
    }
    if (panel_.pathLength > 0.0f && panel_.pathTime != shownPathTime_) {
        // Playing, or the time slider moved: the camera follows the path and flies on from there.
        shownPathTime_ = panel_.pathTime;
        const float start = scene_.cameraPath.keys.front().time;
        fly_.reset(cameraAt(scene_.cameraPath, start + panel_.pathTime), panel_.cameraSpeed);
        return fly_.camera();
    }
    fly_.speed = panel_.cameraSpeed;
    fly_.update(window_->handle(), seconds, !gui_->wantsKeyboard(), !gui_->wantsMouse());
    return fly_.camera();
}

void Viewer::drawFrame(bool scriptedScreenshot) {
    GLFWwindow* w = window_->handle();
    const bool f12 = glfwGetKey(w, GLFW_KEY_F12) == GLFW_PRESS;
    const bool tab = glfwGetKey(w, GLFW_KEY_TAB) == GLFW_PRESS && !gui_->wantsKeyboard();
    if (f12 && !f12Down_) panel_.screenshot = true;
    if (tab && !tabDown_) showPanel_ = !showPanel_;
    if (glfwGetKey(w, GLFW_KEY_ESCAPE) == GLFW_PRESS && !gui_->wantsKeyboard())
        window_->requestClose();
    f12Down_ = f12;
    tabDown_ = tab;

    std::vector<uint8_t> cacheView;
    FrameSource source{renderer_.get(), nullptr};
    if (panel_.cacheView >= 0 && panel_.cacheAvailable) {
        cacheView = makeCacheView(*renderer_, cacheViews()[size_t(panel_.cacheView)].view,
                                  panel_.cachedEffects[size_t(panel_.cacheEffect)],
                                  uint32_t(scene_.settings.cache_rotations));
        source.pixels = &cacheView;
    }
    const bool wantShot = scriptedScreenshot || panel_.screenshot;
    std::vector<float> shot;
    // An out-of-date swapchain (the window changed under it) is rebuilt and the frame drawn again.
    for (int attempt = 0; attempt < 3; ++attempt) {
        gui_->beginFrame();
        const VkExtent2D extent = swapchain_->extent();
        panel_.windowSize = extent;
        panel_.renderSize = renderSize_;
        panel_.frame = frame_;
        panel_.recording = recorder_.recording();
        panel_.recordedKeys = recorder_.path().keys.size();
        if (showPanel_) drawPanel(panel_, float(sceneRect().offset.x), float(extent.height));
        const bool presented = presenter_->draw(source, sceneRect(), wantShot ? &shot : nullptr);
        if (!presented) swapchain_->recreate(window_->framebufferSize());
        if (presented || !shot.empty()) break;
    }
    if (wantShot) {
        std::string path = options_.screenshot;
        if (!scriptedScreenshot) {
            char name[64];
            std::snprintf(name, sizeof name, "out/viewer-%u.png", frame_);
            path = name;
        }
        if (shot.empty()) {
            panel_.message = "screenshot failed: the window's images cannot be read";
        } else {
            const VkExtent2D e = swapchain_->extent();
            writeImage(path, e.width, e.height, shot);
            panel_.message = "wrote " + path;
            std::printf("viewer: wrote %s (%ux%u)\n", path.c_str(), e.width, e.height);
        }
        panel_.screenshot = false;
    }
}

int Viewer::run() {
    double last = glfwGetTime();
    const bool scripted = options_.frames > 0;
    while (!window_->shouldClose()) {
        window_->pollEvents();
        if (window_->shouldClose()) break;
        const double now = glfwGetTime();
        // A scripted run steps time by a fixed amount: the path's step while it plays the path.
        float seconds = float(std::min(now - last, 0.25));
        if (scripted)
            seconds =
                panel_.playPath && options_.frames > 1
                    ? (options_.pathStep > 0.0f ? options_.pathStep
                                                : panel_.pathLength / float(options_.frames - 1))
                    : 1.0f / 30.0f;
        last = now;

        // The window changed size (or the panel was hidden): new swapchain images, and a renderer
        // of the new size, whose histories start empty.
        const VkExtent2D window = window_->framebufferSize();
        if (!sameExtent(window, swapchain_->extent())) {
            std::printf("viewer: window %ux%u -> %ux%u at frame %u\n", swapchain_->extent().width,
                        swapchain_->extent().height, window.width, window.height, frame_);
            swapchain_->recreate(window);
        }
        const VkRect2D rect = sceneRect();
        if (!sameExtent({uint32_t(std::lround(rect.extent.width * options_.renderScale)),
                         uint32_t(std::lround(rect.extent.height * options_.renderScale))},
                        renderSize_))
            rebuildRenderer(Rebuild::Resized);

        const Camera camera = nextCamera(seconds);
        dragLight();
        if (panel_.lightChanged) applyPanelRequests();
        recorder_.update(camera, seconds);
        renderer_->renderFrame(camera);
        panel_.history.add(renderer_->lastFrameProfile());
        panel_.secondsPerFrame =
            scripted ? panel_.history.total.back() / 1000.0f : float(glfwGetTime() - now);
        if (!options_.report.empty()) recordReport(rebuiltThisFrame_);
        rebuiltThisFrame_ = false;

        const bool lastFrame = scripted && frame_ + 1 >= options_.frames;
        drawFrame(lastFrame && !options_.screenshot.empty());
        applyPanelRequests();
        ++frame_;
        if (frame_ == options_.resizeAt)
            window_->setSize(options_.resizeTo.width, options_.resizeTo.height);
        if (lastFrame) break;
    }
    vkDeviceWaitIdle(ctx_->device);

    if (!options_.recordInto.empty()) {
        writeCameraPath(scene_.sourcePath, options_.recordInto, recorder_.path());
        std::printf("viewer: wrote %s (%zu camera keys)\n", options_.recordInto.c_str(),
                    recorder_.path().keys.size());
    }
    if (!options_.report.empty()) {
        report_["frames"] = frame_;
        report_["device"] = ctx_->properties.deviceName;
        report_["validation"] = ctx_->validationEnabled;
        report_["validation_messages"] = ctx_->validationMessageCount();
        report_["panel_width"] = sceneRect().offset.x;
        cli::writeTextAtomically(options_.report, report_.dump(2) + "\n");
    }
    return cli::validationStatus(ctx_->validationMessageCount());
}

} // namespace ssgi::viewer
