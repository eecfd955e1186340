// The pipelines a renderer made, each made once for what makes it (its shaders, set 0's layout,
// push constants and specialization, and for a graphics pipeline its vertex input and targets)
// and handed out again for the same. A renderer made from another's parts (Renderer's taking
// constructor) takes over its store, so a change of settings compiles only the pipelines whose
// specialization it changes; the pipelines are destroyed with the store.
#pragma once

#include "vk/pipeline.h"

#include <deque>
#include <functional>
#include <map>
#include <string>
#include <vector>

namespace ssgi::vk {

class PipelineStore {
public:
    explicit PipelineStore(Context& ctx) : ctx_(ctx) {}
    ~PipelineStore(); // the device must be idle
    PipelineStore(const PipelineStore&) = delete;
    PipelineStore& operator=(const PipelineStore&) = delete;

    // createComputePipeline's pipeline for these arguments, made the first time they are asked.
    const Pipeline& compute(const std::string& shader, const std::vector<LayoutBinding>& bindings,
                            uint32_t pushConstantSize, const Specialization& spec);
    // createGraphicsPipeline's for `desc`, likewise.
    const Pipeline& graphics(const GraphicsPipelineDesc& desc);
    // Pipelines made so far (each once), and how many times one was handed out again.
    size_t made() const { return pipelines_.size(); }
    size_t reused() const { return reused_; }

private:
    // The pipeline held under `key`, made by `make` the first time.
    const Pipeline& held(const std::string& key, const std::function<Pipeline()>& make);
    Context& ctx_;
    std::deque<Pipeline> pipelines_; // a deque: references handed out stay valid
    std::map<std::string, size_t> byKey_;
    size_t reused_ = 0;
};

} // namespace ssgi::vk
