// A transfer pass that clears images to zero: what a pass that accumulates into them, or reads
// an empty value as zero (the world cache's keys and counters), starts from.
#include "passes/passes.h"

namespace ssgi {

void addClearPass(FrameBuild& build, const std::string& name,
                  const std::vector<graph::ImageRef>& images, graph::EnabledFn enabled) {
    std::vector<graph::ImageUse> uses;
    for (const graph::ImageRef& image : images)
        uses.push_back({image, graph::Use::TransferDst});
    build.graph.addPass(
        name, graph::PassKind::Transfer, uses,
        [images](const graph::PassContext& pc) {
            for (const graph::ImageRef& image : images)
                vk::clearToZero(pc.cmd, pc.image(image).image);
        },
        std::move(enabled));
}

} // namespace ssgi
