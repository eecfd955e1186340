// libFuzzer target over compare's image readers (readImage, through OpenImageIO's PNG and
// OpenEXR readers): every input is read as a .png and as an .exr. The reader promises that
// anything it throws is an InputError, that it never takes memory for more than kMaxImageSide
// pixels a side, and that what it returns holds width x height RGBA pixels. A crash, a hang, an
// out-of-memory, a sanitizer report or a broken promise is a finding.
#include "image_io.h"
#include "scene/scene.h"

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <typeinfo>
#include <unistd.h>

namespace fs = std::filesystem;

namespace {

fs::path gDir;

[[noreturn]] void finding(const std::string& message) {
    std::fprintf(stderr, "%s\n", message.c_str());
    std::abort();
}

} // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
    gDir = fs::temp_directory_path() / ("ssgi-fuzz-image-" + std::to_string(getpid()));
    fs::create_directories(gDir);
    std::atexit([] {
        std::error_code ignored;
        fs::remove_all(gDir, ignored);
    });
    return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    for (const char* name : {"input.png", "input.exr"}) {
        const fs::path path = gDir / name;
        std::ofstream(path, std::ios::binary)
            .write(reinterpret_cast<const char*>(data), std::streamsize(size));
        try {
            uint32_t width = 0, height = 0;
            const std::vector<float> rgba = ssgi::readImage(path.string(), width, height);
            if (width < 1 || height < 1 || width > uint32_t(ssgi::kMaxImageSide) ||
                height > uint32_t(ssgi::kMaxImageSide) || rgba.size() != size_t(width) * height * 4)
                finding("reader broke its promise: a size outside 1..kMaxImageSide or pixels "
                        "that do not match it");
        } catch (const ssgi::InputError&) {
            // The reader doing its job.
        } catch (const std::exception& error) {
            finding(std::string("threw ") + typeid(error).name() +
                    " instead of InputError: " + error.what());
        }
    }
    return 0;
}
