#include "vk/pipeline_store.h"

namespace ssgi::vk {

namespace {

void append(std::string& key, const std::vector<LayoutBinding>& bindings) {
    for (const LayoutBinding& b : bindings)
        key += " " + std::to_string(int(b.type)) + ":" + b.name + (b.readOnly ? ":readonly" : "") +
               ":" + std::to_string(int(b.format));
}

void append(std::string& key, const Specialization& spec) {
    for (const SpecConstant& c : spec.constants)
        key += " " + c.name + "=" + std::to_string(c.value);
}

} // namespace

PipelineStore::~PipelineStore() {
    for (Pipeline& p : pipelines_)
        destroyPipeline(ctx_, p);
}

const Pipeline& PipelineStore::held(const std::string& key, const std::function<Pipeline()>& make) {
    if (const auto found = byKey_.find(key); found != byKey_.end()) {
        ++reused_;
        return pipelines_[found->second];
    }
    pipelines_.push_back(make());
    byKey_[key] = pipelines_.size() - 1;
    return pipelines_.back();
}

const Pipeline& PipelineStore::compute(const std::string& shader,
                                       const std::vector<LayoutBinding>& bindings,
                                       uint32_t pushConstantSize, const Specialization& spec) {
    std::string key = "compute " + shader + " push " + std::to_string(pushConstantSize) + " spec";
    append(key, spec);
    key += " set0";
    append(key, bindings);
    return held(
        key, [&] { return createComputePipeline(ctx_, shader, bindings, pushConstantSize, spec); });
}

const Pipeline& PipelineStore::graphics(const GraphicsPipelineDesc& desc) {
    std::string key = "graphics " + desc.vertexShader + " + " + desc.fragmentShader + " stride " +
                      std::to_string(desc.vertices.stride) + " attributes";
    for (const VkVertexInputAttributeDescription& a : desc.vertices.attributes)
        key += " " + std::to_string(a.location) + ":" + std::to_string(a.binding) + ":" +
               std::to_string(int(a.format)) + ":" + std::to_string(a.offset);
    key += " colour";
    for (const VkFormat format : desc.colorFormats)
        key += " " + std::to_string(int(format));
    key += " depth " + std::to_string(int(desc.depthFormat)) + " textures " +
           std::to_string(uint64_t(desc.textureSetLayout)) + " push " +
           std::to_string(desc.pushConstantSize) + " vertex spec";
    append(key, desc.vertexSpec);
    key += " fragment spec";
    append(key, desc.fragmentSpec);
    key += " set0";
    append(key, desc.bindings);
    return held(key, [&] { return createGraphicsPipeline(ctx_, desc); });
}

} // namespace ssgi::vk
