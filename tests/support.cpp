#include "support.h"

#include "renderer.h"

#include <memory>

namespace ssgi::test {

vk::Context& context() {
    static std::unique_ptr<vk::Context> ctx =
        std::make_unique<vk::Context>(vk::ContextOptions{/*validation=*/true, /*deviceName=*/""});
    return *ctx;
}

std::string sourcePath(const std::string& relative) {
    return std::string(SSGI_SOURCE_DIR) + "/" + relative;
}

std::string sharedScene(const std::string& name) {
    return std::string(SSGI_SOURCE_DIR) + "/../shared/scenes/" + name;
}

Frame render(const Scene& scene, uint32_t width, uint32_t height, uint32_t frames) {
    Renderer renderer(context(), scene, {width, height, "final"});
    for (uint32_t i = 0; i < frames; ++i)
        renderer.renderFrame(scene.camera);
    Frame f;
    f.width = width;
    f.height = height;
    auto read = [&](const char* name) {
        return renderer.frameGraph().find(name).valid() ? renderer.readImage(name)
                                                        : std::vector<float>();
    };
    f.direct = read("direct");
    f.position = read("gbuffer.position");
    f.normal = read("gbuffer.normal");
    f.albedo = read("gbuffer.albedo");
    f.hdr = read("hdr");
    f.ldr = read("ldr");
    f.ao = read("ao");
    f.indirect = read("indirect");
    f.ssdo = read("ssdo");
    f.shadow = read("shadow");
    return f;
}

} // namespace ssgi::test
