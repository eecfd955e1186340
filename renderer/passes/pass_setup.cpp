#include "passes/pass_setup.h"

namespace ssgi {

const vk::Pipeline& PassSetup::computePipeline(const ComputePassDesc& desc,
                                               const std::vector<vk::LayoutBinding>& layout) {
    std::string key = desc.shader + " push " + std::to_string(desc.pushSize) + " spec";
    for (int32_t v : desc.spec.values)
        key += " " + std::to_string(v);
    for (const vk::LayoutBinding& b : layout)
        key += " " + std::to_string(int(b.type)) + ":" + b.name + (b.readOnly ? ":readonly" : "");
    const auto found = computePipelines.find(key);
    if (found != computePipelines.end()) return pipelines[found->second];
    pipelines.push_back(
        vk::createComputePipeline(ctx, desc.shader, layout, desc.pushSize, desc.spec));
    computePipelines[key] = pipelines.size() - 1;
    return pipelines.back();
}

shader::IndirectConstants indirectConstants(const PassSetup& s, const EffectCache* cache,
                                            VkExtent2D gather) {
    shader::IndirectConstants c{};
    c.rotation = s.patternRotation;
    c.scale = s.patternScale;
    c.radius = float(s.model.settings.indirect_radius);
    c.radialOffset = radialOffset(s, cache);
    c.visibilityStart = float(s.model.settings.indirect_visibility_start);
    c.width = int(gather.width);
    c.height = int(gather.height);
    c.cache = cacheConstants(s, cache);
    return c;
}

} // namespace ssgi
