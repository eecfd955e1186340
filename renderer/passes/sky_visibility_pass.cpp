// sky.maps and sky_visibility: the sky's visibility beyond the screen. sky.maps draws the
// scene's depth from directions spread over the whole sphere (orthographic, around the bounding
// sphere of what it draws) into the tiles of one depth atlas; sky_visibility looks every pixel
// up in each map, and tests the scene's single quads and triangles (floors, walls) exactly, and
// writes the fraction of the sky's light that arrives past the occluders farther than the AO's
// radius (sky_visibility.comp). A static scene's maps are drawn once and again only after an
// object moved. The lookup is a cached effect: a property of the surface point, computed without
// noise, so that one computation is its value (CachedEffect::exact), reused wherever it
// reprojects while the camera moves, and computed again for new surfaces, where its resampling
// has blurred it past its budget (cache_blur_sky_visibility), in the refresh tile, and after the
// maps were drawn again (a moved object restarts it). Where the world cache's cells hold the
// sky's visibility instead (skyInWorldCache: world_cache_pass.cpp reads the maps), only sky.maps
// is made here.
//   reads:  gbuffer.view_depth, gbuffer.normal, sky.maps (and its cache's history)
//   writes: sky.maps, sky_visibility, sky_visibility.history
#include "passes/passes.h"

#include "scene/animation.h"
#include "shared.h"

#include <cmath>
#include <cstring>
#include <limits>

namespace ssgi {

namespace {

// The sky's occluders, split in two. A floor or a wall (a mesh of one or two triangles, not
// alpha-masked, not moved by a path) is tested exactly; the rest is drawn into the maps, whose
// sphere then fits the rest alone: the bunny on its 20 m floor filled two texels of a map
// around the floor, and of a map around itself all of it.
struct SkyOccluders {
    std::vector<bool> mapped; // per instance: drawn into the maps
    Aabb mappedBounds;        // theirs, wherever their paths take them
    shader::SkyTriangles exact{};
};

SkyOccluders splitSkyOccluders(const Scene& scene, const glm::dvec3& gpuOrigin) {
    SkyOccluders o;
    std::vector<bool> moving(scene.instances.size());
    for (const ObjectPath& path : scene.objectPaths)
        for (int i : path.instances)
            moving[size_t(i)] = true;
    // Where the instances stand before the paths start and at every key of every path.
    std::vector<std::vector<glm::mat4>> poses{
        instanceTransformsAt(scene, std::numeric_limits<float>::lowest())};
    for (const ObjectPath& path : scene.objectPaths)
        for (const ObjectKey& key : path.keys)
            poses.push_back(instanceTransformsAt(scene, key.time));
    int triangles = 0;
    for (size_t i = 0; i < scene.instances.size(); ++i) {
        const Instance& instance = scene.instances[i];
        const Mesh& mesh = scene.meshes[size_t(instance.mesh)];
        const int count = int(mesh.indices.size() / 3);
        const bool exact = count > 0 && count <= 2 && !moving[i] &&
                           !scene.materials[size_t(mesh.material)].alphaMask &&
                           triangles + count <= SKY_TRIANGLES_MAX;
        o.mapped.push_back(!exact);
        if (exact) {
            for (size_t k = 0; k < size_t(3 * count); ++k) {
                const glm::vec3 p =
                    instance.transform * glm::vec4(mesh.vertices[mesh.indices[k]].position, 1.0f);
                o.exact.corners[3 * triangles + k] =
                    glm::vec4(glm::vec3(glm::dvec3(p) - gpuOrigin), 1.0f);
            }
            triangles += count;
            continue;
        }
        for (const std::vector<glm::mat4>& pose : poses) {
            const Aabb box = instanceBounds(scene, i, pose[i]);
            o.mappedBounds.extend(box.min);
            o.mappedBounds.extend(box.max);
        }
    }
    o.exact.count.x = triangles;
    if (o.mappedBounds.empty()) o.mappedBounds = scene.bounds; // nothing to draw: any sphere
    return o;
}

} // namespace

SkyMaps addSkyMapsPass(FrameBuild& build) {
    const Scene& scene = build.scene;
    const int count = int(scene.settings.sky_visibility_directions);
    const int tileSize = int(scene.settings.sky_visibility_map_size);
    const int perRow = int(std::ceil(std::sqrt(double(count))));
    const VkExtent2D atlas{uint32_t(perRow * tileSize),
                           uint32_t(((count + perRow - 1) / perRow) * tileSize)};
    const uint32_t limit = build.ctx.properties.limits.maxImageDimension2D;
    if (atlas.width > limit || atlas.height > limit)
        throw InputError("sky_visibility_map_size " + std::to_string(tileSize) + " with " +
                         std::to_string(count) + " directions needs a " +
                         std::to_string(atlas.width) + "x" + std::to_string(atlas.height) +
                         " atlas, beyond this device's largest 2D image (" + std::to_string(limit) +
                         ")");
    const SkyOccluders occluders = splitSkyOccluders(scene, build.gpuOrigin);
    // In the GPU's coordinates, as the G-buffer and the draws are.
    const Aabb& drawn = occluders.mappedBounds;
    const glm::vec3 centre = glm::vec3(glm::dvec3(drawn.center()) - build.gpuOrigin);
    // Above zero for a scene at one point, with no floor in units (1e-6 was all of a scene of
    // 1e-9 units).
    const float radius =
        std::max(0.5f * glm::length(drawn.size()) * 1.02f, std::numeric_limits<float>::min());
    const shader::SkyMapView view{glm::vec4(centre, radius),
                                  glm::ivec4(0, count, perRow, tileSize)};

    // 16-bit depths: the maps are orthographic, so a step is the sphere's diameter / 65536: a
    // 256th of a texel of the default 256-texel maps, a 16th at the largest (4096), below the
    // test's offsets (more than a texel).
    const VkFormat depthFormat = VK_FORMAT_D16_UNORM;
    const graph::ImageRef maps = build.graph.createImage(
        "sky.maps", depthFormat, atlas,
        VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT, true);
    // One uniform buffer per map: the draw binds the map's view where the camera's would be.
    std::vector<VkBuffer> views;
    for (int k = 0; k < count; ++k) {
        shader::SkyMapView map = view;
        map.tile.x = k;
        views.push_back(build.uniformBuffer(&map, sizeof(map)).buffer);
    }
    vk::GraphicsPipelineDesc desc;
    desc.vertices = sceneVertexInput();
    desc.vertexShader = "sky_depth.vert";
    desc.fragmentShader = "sky_depth.frag";
    desc.depthFormat = depthFormat;
    desc.bindings = {{VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, "MapBlock"},
                     {VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, "baseColorTexture"}};
    desc.pushConstantSize = sizeof(shader::DrawConstants);
    const vk::Pipeline masked = build.graphicsPipeline(desc);
    // The opaque materials' draws with no fragment shader, as the shadow map's (scene_pass.cpp):
    // sky_depth.frag's discard would run it for each of their fragments. sky.maps (lavapipe,
    // 256x256) 1263 -> 1030 ms on the bunny, 1070 -> 742 on Sponza, 54 -> 27 on the scrub pine.
    const vk::Pipeline opaque = build.graphicsPipeline(depthOnly(desc));

    using graph::Use;
    build.graph.addPass(
        "sky.maps", graph::PassKind::Graphics, {{maps, Use::DepthAttachment}},
        [&build, maps, atlas, views, perRow, tileSize, opaque, masked,
         mapped = occluders.mapped](const graph::PassContext& pc) {
            VkRenderingAttachmentInfo depth{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
            depth.imageView = pc.image(maps).view;
            depth.imageLayout = VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL;
            depth.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR; // 1: nothing toward the far side
            depth.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
            depth.clearValue.depthStencil = {1.0f, 0};
            VkRenderingInfo info{VK_STRUCTURE_TYPE_RENDERING_INFO};
            info.renderArea = {{0, 0}, atlas};
            info.layerCount = 1;
            info.pDepthAttachment = &depth;
            vkCmdBeginRendering(pc.cmd, &info);
            for (size_t k = 0; k < views.size(); ++k) {
                const float x = float(int(k) % perRow * tileSize);
                const float y = float(int(k) / perRow * tileSize);
                VkViewport viewport{x, y, float(tileSize), float(tileSize), 0, 1};
                VkRect2D scissor{{int32_t(x), int32_t(y)},
                                 {uint32_t(tileSize), uint32_t(tileSize)}};
                vkCmdSetViewport(pc.cmd, 0, 1, &viewport);
                vkCmdSetScissor(pc.cmd, 0, 1, &scissor);
                build.sceneGpu.draw(pc.cmd, opaque, masked, views[k], sizeof(shader::SkyMapView),
                                    {}, mapped);
            }
            vkCmdEndRendering(pc.cmd);
        },
        [](const FrameState& frame) { return frame.drawSkyMaps; });

    SkyMaps out;
    out.atlas = maps;
    out.exactTriangles = build.uniformBuffer(&occluders.exact, sizeof(occluders.exact));
    out.view = view;
    // Occluders nearer than the AO's radius are the AO's; with no AO, only a few texels' worth
    // of nearness is left out (the map's own resolution).
    const float texel = 2.0f * radius / float(tileSize);
    const float nearest = scene.settings.ao && !scene.settings.ssdo ? aoRadius(scene) : 0.0f;
    out.aoReach = std::max(nearest, 3.0f * texel);
    out.normalOffset = 1.5f * texel;
    return out;
}

graph::ImageRef addSkyVisibilityPass(FrameBuild& build, const GBufferAndRsm& in,
                                     const SkyMaps& maps) {
    using graph::Use;
    shader::SkyVisibilityConstants constants{};
    constants.maps = maps.view;
    constants.aoReach = maps.aoReach;
    constants.normalOffset = maps.normalOffset;
    CachedComputePass pass;
    pass.effect = {.name = "sky_visibility",
                   .lightDependent = false,
                   .scalar = false,
                   .motionTest = MOTION_RESTART_ALL,
                   .exact = true,
                   .viewIndependent = true};
    pass.term = "sky-visibility";
    pass.shader = "sky_visibility.comp";
    pass.inputs = {{"gbufferViewDepth", in.gbuffer.viewDepth, Use::Sampled},
                   {"gbufferNormal", in.gbuffer.normal, Use::Sampled},
                   {"skyMaps", maps.atlas, Use::Sampled}};
    pass.uniforms = {{"TrianglesBlock", maps.exactTriangles}};
    pass.pushSize = sizeof(shader::SkyVisibilityConstants);
    return addCachedComputePass(build, in.gbuffer, std::move(pass),
                                [constants](const CachedRecorder& r) { r.dispatch(constants); });
}

} // namespace ssgi
