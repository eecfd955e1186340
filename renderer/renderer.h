// The frame: wires the passes into the graph in declared order and renders frames of a scene.
#pragma once

#include "frame_state.h"
#include "graph/frame_graph.h"
#include "passes/frame_build.h"
#include "scene/scene.h"
#include "scene/sealed.h"
#include "scene_gpu.h"
#include "world_grid.h"

#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace ssgi {

// Names of the debug views the composite can show in place of the final image.
const std::vector<std::string>& viewNames();

struct RenderOptions {
    uint32_t width = 512, height = 512;
    std::string view = "final";
    // Images readImage() must find whole after a frame although a later pass reuses their memory
    // (FrameGraph::keep): an effect's raw output ("ao", "indirect", ...), for tests and the
    // benchmarks; "*" keeps every image. Names the frame lacks are passed over. What needs no
    // keeping: the outputs, the G-buffer, the histories, and whatever the last passes wrote.
    std::vector<std::string> keep;
    // The frame at which the sampling patterns' sequence (their turn, size and offsets, the
    // VPL subsets' turn, the flux draw) starts. A reference renderer that must not share the
    // samples of renderers started at 0 starts elsewhere (the stability suite's converged image).
    uint32_t patternStart = 0;
    // The frame graph keeps the last frame's barriers and commands (FrameGraph::lastBarriers),
    // for tests that inspect them.
    bool logRecording = false;
};

class Renderer {
public:
    // Throws InputError for absurd options (size 0, beyond the device's limit, unknown view).
    Renderer(vk::Context& ctx, const Scene& scene, const RenderOptions& options);
    // A renderer made anew from `previous`'s parts, for a change of settings: `scene` is
    // previous's with other settings (or light, or camera): the same meshes, materials, textures
    // and instances, whose copy on the device it takes over, with the pipelines previous made
    // (vk/pipeline_store.h), which its passes take where their shaders, layouts and
    // specializations are unchanged. Everything else starts anew: its frames are those of a
    // renderer made from nothing, bit for bit. `previous` is checked against `options` first
    // (InputError, and previous is untouched); past that, it is left empty, to be destroyed.
    Renderer(vk::Context& ctx, const Scene& scene, const RenderOptions& options,
             Renderer& previous);
    ~Renderer();
    // Whether another renderer took this one's parts (above): only destruction is left.
    bool emptied() const { return !sceneGpu_; }
    // Pipelines made by this renderer and those it took its parts from, and times one was
    // handed to a pass again (a test's measure of what a change of settings compiled).
    size_t pipelinesMade() const { return pipelines_->made(); }
    size_t pipelinesReused() const { return pipelines_->reused(); }

    // Renders one frame from `camera`, waits for it and collects its pass timings.
    void renderFrame(const Camera& camera);
    // Moves the light from the next frame on. The cached effects that depend on it (shadow,
    // indirect light, SSDO's bounce) start over; AO, which does not, keeps its history.
    void setLight(const SpotLight& light);
    // Whether the last frame's light was sealed off from its camera by a closed mesh
    // (scene/sealed.h), and by which. Such a frame has no light from it: no direct light and no
    // virtual lights (their flux zero), as no path joins the two. Decided for every frame whose
    // camera, light or objects moved; a change is a change of the light (above). The first
    // sealed frame says so, once for the renderer.
    const std::optional<Seal>& seal() const { return seal_; }
    // Places the scene's moving objects (its object paths) as they are at `seconds`, from the
    // next frame on. What an object's move can change restarts: the AO within its radius of the
    // object's old and new place and the shadow on paths to the light passing near them, per
    // pixel; the indirect light and SSDO (whose bounce any moved shadow changes) whole; the RSM
    // is drawn again. Before the first call the objects stand at their paths' first keys.
    void setTime(float seconds);
    // A camera cut: the next frame starts every cached history afresh. Also done by itself for a
    // camera that turns or jumps beyond the cache_cut_* settings between two frames, and by
    // setTime() when the camera path's keys marked "cut" are crossed.
    void cut() { cutRequested_ = true; }
    // A resize: this renderer, new and of another size, goes on from where `previous` (of the
    // same scene) stopped: its camera, light, objects and pattern sequence, and, with the
    // cache_resize setting on, every cached effect's history, which the first frame reprojects
    // at its old size as it reprojects any last frame (temporal.glsl). Before the first frame.
    void continueFrom(Renderer& previous);
    // Cuts so far, requested or automatic (for tests and the programs' reports).
    uint32_t cuts() const { return cuts_; }
    // Shows another view (see viewNames()) from the next frame on; the caches are untouched.
    void setView(const std::string& view);
    const SpotLight& light() const { return light_; }
    const std::vector<PassTiming>& timings() const { return graph_->timings(); }
    // The last frame's passes and the host's clock around its submission.
    FrameProfile lastFrameProfile() const;

    // Reads an image of the last frame by name ("hdr", "ldr", "direct", "gbuffer.position",
    // "gbuffer.normal", "gbuffer.albedo", "gbuffer.depth", "rsm.vpls", ...) as RGBA floats. A
    // cached effect's history is "<effect>.history" (the blended value) and "<effect>.meta"
    // (world position, the effect's rotation count in alpha: its "<effect>.count" beside the
    // G-buffer's positions, which every cached effect shares; "<effect>.count" alone is the
    // count in red), as the last frame wrote them. "gbuffer.position" is reconstructed from
    // "gbuffer.view_depth" as the passes do (gbuffer_position.glsl; w = 1 on geometry).
    // "rsm.vpls" (RGBA32UI) is decoded as rsm_vpl.glsl does: each VPL's flux, and its distance
    // along the light's axis in alpha (0 where nothing was drawn). A
    // screen image is read at size(): its guard band (the guard_band setting) left out.
    std::vector<float> readImage(const std::string& name);
    // Whether readImage(name) finds an image in this frame.
    bool hasImage(const std::string& name) const;
    // The output's size ("hdr", "ldr"); the screen images the passes write are larger by the
    // guard band on each side.
    VkExtent2D size() const { return build_->output().extent; }
    // For the viewer: records into cmd, after the last frame, the barrier that makes image `name`
    // ("ldr") a transfer source, and returns it.
    const vk::Image& prepareCopySource(VkCommandBuffer cmd, const std::string& name);
    // The cached effects of this frame ("shadow", "ao", ...), and the pixels of the tile a cached
    // effect refreshed in the last frame, in the output's pixels (extent 0 when none, or when it
    // lay in the guard band).
    std::vector<std::string> cachedEffects() const;
    // The world cache's counters of the last frame (indirect_method 3; WORLD_STAT_* of
    // shared.h), or none without it.
    struct WorldCacheCounts {
        uint32_t live = 0, filled = 0, refreshed = 0, evicted = 0, full = 0, entries = 0;
        uint32_t cut = 0; // gather samples a loop limit left out (WORLD_STAT_CUT)
        // world_half_res: the pixels world.lookup_edges looked up alone (WORLD_STAT_EDGES).
        uint32_t edges = 0;
    };
    std::optional<WorldCacheCounts> worldCacheCounts();
    // Where the world cache's voxel grid lay in the last frame, in the GPU's coordinates
    // (frame_uniforms.h gpuOrigin); its images are "world.voxels" and "world.voxel_distance".
    const WorldGridPlacement& worldGrid() const { return worldGrid_; }
    VkRect2D refreshedTile(const std::string& effect) const;
    const graph::FrameGraph& frameGraph() const { return *graph_; }

private:
    Renderer(vk::Context& ctx, const Scene& scene, const RenderOptions& options,
             Renderer* previous);
    // The image readImage(name) downloads (a pair's side the last frame wrote), or none; the
    // cache whose "<effect>.meta" `name` is (composed of two images), or none.
    graph::ImageRef imageNamed(const std::string& name) const;
    const EffectCache* metaOf(const std::string& name) const;
    std::vector<float> readRsmVpls(graph::ImageRef ref);     // readImage's decoding of "rsm.vpls"
    std::vector<float> readHdr(graph::ImageRef ref);         // and of "hdr"
    std::vector<float> readReprojection(graph::ImageRef ref, // and of "reprojection"
                                        std::optional<VkRect2D> area);
    void updateUniforms(const Camera& camera);
    void updateSeal(const Camera& camera); // seal_ for this frame's camera
    void lightChanged();                   // what a change of the light restarts (setLight)
    // What this frame runs and with which patterns (frame_state.h), once the camera is known.
    FrameState decideFrame();
    bool startsAfresh(const Camera& camera) const;
    std::vector<glm::mat4> gpuTransforms() const; // transforms_, moved to the GPU's origin
    void uploadTransforms();                      // gpuTransforms() to the scene's draws
    void release(); // what the destructor gives back, also when the constructor fails
    // The taking constructor's: the images previous drew only once (the light's maps, the sky
    // maps, the voxel grid) taken over where this frame would draw the same.
    void takeDrawn(Renderer& previous);

    vk::Context& ctx_;
    const Scene& scene_;
    // scene_'s settings when this renderer was made (a caller such as the viewer may change the
    // scene's before making the next renderer from this one's parts: takeDrawn compares these).
    const Settings builtSettings_;
    std::unique_ptr<SceneGpu> sceneGpu_;
    std::unique_ptr<vk::PipelineStore> pipelines_; // outlives build_, which takes from it
    std::unique_ptr<graph::FrameGraph> graph_;
    std::unique_ptr<FrameBuild> build_;
    SpotLight light_;
    uint32_t frameIndex_ = 0;
    uint32_t patternStart_ = 0; // RenderOptions::patternStart
    uint32_t patternFrame() const { return patternStart_ + frameIndex_; }
    vk::HostSpan lastSubmission_;
    uint32_t stillFrames_ = 0;      // frames in a row with this camera and light
    uint32_t gbufferSidesHeld_ = 0; // sides of this renderer's G-buffer pair that hold its view
    bool rsmStale_ = true;          // the light changed since the RSM was drawn
    bool skyMapsStale_ = true;      // an object moved since the sky maps were drawn
    bool voxelsStale_ = true;       // the light or an object moved since the voxel grid was drawn
    bool lightMoved_ = false;       // the light changed since the last frame
    bool worldCacheEmpty_ = true;   // no frame has filled the world cache's table yet
    bool tookDrawn_ = false;        // takeDrawn kept some of them
    int view_ = 0;                  // what the composite shows (its place in kViews)
    FrameState lastFrame_;          // what the last frame ran
    std::vector<glm::mat4> transforms_; // where the instances stand
    std::vector<Aabb> moved_;           // boxes of the objects moved since the last frame
    WorldGridPlacement worldGrid_;      // the world cache's voxel grid, in the GPU's coordinates
    glm::mat4 previousViewProjection_{1.0f};
    glm::mat4 previousPixelToWorld_{1.0f}; // FrameUniforms::pixelToWorld of the last frame
    glm::mat4 reprojectedInto_{1.0f};      // its previousViewProjection: what its reprojection used
    glm::vec3 lastLightColor_{0.0f};       // its lightColor (the RSM's flux, rsm_vpl.glsl)
    Camera previousCamera_;
    bool cutRequested_ = false;
    uint32_t cuts_ = 0;
    // The time before every path's first key, where the objects stand before the first setTime().
    static constexpr float kBeforeFirstKey = std::numeric_limits<float>::lowest();
    float time_ = kBeforeFirstKey; // the last setTime()
    glm::dvec3 origin_{0.0}; // world point at the GPU's origin (renderer.cpp: gpuOrigin)
    LightSeals seals_;
    std::optional<Seal> seal_;
    bool sealStale_ = true; // the light or an object moved since seal_ was decided
    bool sealWarned_ = false;
    Camera sealCamera_; // the camera seal_ was decided for
};

} // namespace ssgi
