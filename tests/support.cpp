#include "support.h"

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

} // namespace ssgi::test
