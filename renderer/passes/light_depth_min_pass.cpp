// light_depth_min: the light's depth in blocks of the RSM's texels, each block's nearest, as a
// distance along the light's axis, for the bounce's visibility test to ask the light
// (indirect_visibility_light; indirect_visibility.glsl, lightSeesOpenAbove). A map this small
// stays in a CPU's cache: on lavapipe at 256x256 (uncached frames) the bounce's gather took
// 275 ms reading the 2048-texel shadow map, 192 the 1024-texel RSM depth and 94 a 256-texel
// image, against 64 without the check (the Cornell box). A half float's image took Sponza's
// gather from 83 to 80 ms along its path, but the AO pass of the bunny's moving frames at
// 512x512 went from 54 to 170 ms with it (the AO does not read it; the cause was not found), and
// it is not used. The nearest of a block answers the check conservatively: what it calls open is
// open at every texel of the block. Drawn on the light's frames (onLightFrames), with
// light_depth_min.comp.
//   reads:  rsm.depth
//   writes: light_depth_min (R32F, kLightDepthMinSide texels a side, or the RSM's if smaller)
#include "passes/passes.h"

#include <algorithm>

namespace ssgi {

namespace {
constexpr uint32_t kLightDepthMinSide = 256;
}

graph::ImageRef addLightDepthMinPass(FrameBuild& build, const Rsm& rsm) {
    const uint32_t side = std::min(kLightDepthMinSide, build.rsmSize.width);
    const int block = int((build.rsmSize.width + side - 1) / side);
    const graph::ImageRef nearest =
        build.graph.createImage("light_depth_min", VK_FORMAT_R32_SFLOAT, VkExtent2D{side, side},
                                VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT, true);
    ComputePassDesc desc{"light_depth_min", "light_depth_min.comp"};
    desc.images = {{"rsmDepth", rsm.depth, graph::Use::Sampled},
                   {"nearestDepth", nearest, graph::Use::StorageWrite}};
    desc.spec = vk::Specialization{{{"BLOCK", block}}};
    addComputePass(
        build, std::move(desc), [side](const ComputeRecorder& r) { r.dispatch(side, side); },
        onLightFrames(build));
    return nearest;
}

ShaderImage lightDepthMinInput(const GBufferAndRsm& in) {
    return {"lightDepthMin", in.lightDepthMin.valid() ? in.lightDepthMin : in.rsm.depth,
            graph::Use::Sampled};
}

} // namespace ssgi
