#include "image_io.h"

#include "scene/scene.h"

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <unistd.h>

namespace ssgi {

namespace fs = std::filesystem;

void writeImage(const std::string& path, uint32_t width, uint32_t height,
                const std::vector<float>& rgba) {
    const std::string ext = fs::path(path).extension().string();
    const bool exr = ext == ".exr";
    if (!exr && ext != ".png") throw InputError(path + ": output must end in .png or .exr");
    const fs::path parent = fs::path(path).parent_path();
    std::error_code ec;
    if (!parent.empty()) fs::create_directories(parent, ec);
    if (ec)
        throw InputError(path + ": cannot create folder " + parent.string() + ": " + ec.message());

    // The temporary keeps the extension so that OpenImageIO picks the same format for it.
    const fs::path tmp =
        parent / (".tmp-" + std::to_string(getpid()) + "-" + fs::path(path).filename().string());
    auto out = OIIO::ImageOutput::create(path);
    if (!out) throw InputError(path + ": no writer for this format: " + OIIO::geterror());
    const int channels = exr ? 3 : 4;
    OIIO::ImageSpec spec(int(width), int(height), channels,
                         exr ? OIIO::TypeDesc::HALF : OIIO::TypeDesc::UINT8);
    if (exr) spec.attribute("compression", "zip");
    if (!out->open(tmp.string(), spec)) throw InputError(path + ": " + out->geterror());
    std::vector<float> pixels(size_t(width) * height * channels);
    for (size_t i = 0; i < size_t(width) * height; ++i)
        for (int c = 0; c < channels; ++c) {
            float v = rgba[4 * i + c];
            pixels[channels * i + c] = exr ? v : std::clamp(v, 0.0f, 1.0f);
        }
    const bool ok = out->write_image(OIIO::TypeDesc::FLOAT, pixels.data()) && out->close();
    if (!ok) {
        const std::string error = out->geterror();
        fs::remove(tmp, ec);
        throw InputError(path + ": writing failed: " + error);
    }
    fs::rename(tmp, path, ec);
    if (ec) {
        fs::remove(tmp, ec);
        throw InputError(path + ": cannot move the finished file into place: " + ec.message());
    }
}

std::vector<float> readImage(const std::string& path, uint32_t& width, uint32_t& height) {
    auto in = OIIO::ImageInput::open(path);
    if (!in) throw InputError(path + ": cannot read image: " + OIIO::geterror());
    const OIIO::ImageSpec& spec = in->spec();
    width = uint32_t(spec.width);
    height = uint32_t(spec.height);
    std::vector<float> pixels(size_t(width) * height * spec.nchannels);
    if (!in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, pixels.data()))
        throw InputError(path + ": " + in->geterror());
    std::vector<float> rgba(size_t(width) * height * 4, 1.0f);
    for (size_t i = 0; i < size_t(width) * height; ++i)
        for (int c = 0; c < std::min(spec.nchannels, 4); ++c)
            rgba[4 * i + c] = pixels[spec.nchannels * i + c];
    return rgba;
}

} // namespace ssgi
