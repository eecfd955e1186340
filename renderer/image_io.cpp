#include "image_io.h"

#include "scene/scene.h"

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <stdexcept>
#include <sys/stat.h>
#include <unistd.h>

namespace ssgi {

namespace fs = std::filesystem;

namespace {

// Values a file of this kind would store: RGB for EXR, RGBA clamped to [0, 1] for PNG.
std::vector<float> storedValues(const ImageFile& image, bool exr) {
    const int channels = exr ? 3 : 4;
    const size_t pixels = size_t(image.width) * image.height;
    std::vector<float> values(pixels * channels);
    for (size_t i = 0; i < pixels; ++i)
        for (int c = 0; c < channels; ++c) {
            const float v = (*image.rgba)[4 * i + c];
            values[channels * i + c] = exr || !std::isfinite(v) ? v : std::clamp(v, 0.0f, 1.0f);
        }
    return values;
}

fs::path besideTarget(const std::string& path, const char* prefix) {
    const fs::path target(path);
    return target.parent_path() /
           (prefix + std::to_string(getpid()) + "-" + target.filename().string());
}

// Writes one image to its temporary name; throws (leaving nothing there) on failure.
void writeTemporary(const ImageFile& image, const fs::path& tmp) {
    const std::string& path = image.path;
    const bool exr = fs::path(path).extension() == ".exr";
    const std::vector<float> values = storedValues(image, exr);
    // Nothing non-finite is ever written: a NaN or Inf is a renderer's failure (exit status 1).
    const size_t bad = size_t(
        std::count_if(values.begin(), values.end(), [](float v) { return !std::isfinite(v); }));
    if (bad > 0)
        throw std::runtime_error(path + ": " + std::to_string(bad) + " of " +
                                 std::to_string(values.size()) +
                                 " values are NaN or infinite; no image written");
    // Half floats hold up to 65504; a brighter image is stored as 32-bit floats rather than as
    // infinity (what the half conversion would make of it).
    constexpr float kHalfMax = 65504.0f;
    const bool fitsHalf = std::all_of(values.begin(), values.end(),
                                      [&](float v) { return std::fabs(v) <= kHalfMax; });
    auto out = OIIO::ImageOutput::create(path);
    if (!out) throw InputError(path + ": no writer for this format: " + OIIO::geterror());
    const int channels = exr ? 3 : 4;
    OIIO::ImageSpec spec(int(image.width), int(image.height), channels,
                         !exr       ? OIIO::TypeDesc::UINT8
                         : fitsHalf ? OIIO::TypeDesc::HALF
                                    : OIIO::TypeDesc::FLOAT);
    if (exr) spec.attribute("compression", "zip");
    if (!out->open(tmp.string(), spec)) throw InputError(path + ": " + out->geterror());
    const bool ok = out->write_image(OIIO::TypeDesc::FLOAT, values.data()) && out->close();
    if (!ok) {
        const std::string error = out->geterror();
        std::error_code ec;
        fs::remove(tmp, ec);
        throw InputError(path + ": writing failed: " + error);
    }
}

} // namespace

void writeImages(const std::vector<ImageFile>& images) {
    for (const ImageFile& image : images) {
        const std::string ext = fs::path(image.path).extension().string();
        if (ext != ".exr" && ext != ".png")
            throw InputError(image.path + ": output must end in .png or .exr");
    }
    std::vector<fs::path> temporaries, backups;
    std::error_code ec;
    auto removeAll = [&](const std::vector<fs::path>& paths) {
        for (const fs::path& p : paths)
            fs::remove(p, ec);
    };
    try {
        for (const ImageFile& image : images) {
            const fs::path parent = fs::path(image.path).parent_path();
            if (!parent.empty() && !fs::is_directory(parent, ec)) {
                fs::create_directories(parent, ec);
                if (ec)
                    throw InputError(image.path + ": cannot create folder " + parent.string() +
                                     ": " + ec.message());
            }
            // The temporary keeps the extension so that OpenImageIO picks the same format.
            temporaries.push_back(besideTarget(image.path, ".tmp-"));
            writeTemporary(image, temporaries.back());
        }
    } catch (...) {
        removeAll(temporaries);
        throw;
    }
    // Every file is complete; move them into place. A file already at a target is kept under a
    // second name (a hard link) until all have moved, so a failure puts back what was there.
    std::vector<bool> hadOld(images.size(), false);
    for (size_t i = 0; i < images.size(); ++i) {
        const std::string& path = images[i].path;
        backups.push_back(besideTarget(path, ".old-"));
        struct stat status {};
        hadOld[i] = ::lstat(path.c_str(), &status) == 0 && !S_ISDIR(status.st_mode) &&
                    ::link(path.c_str(), backups[i].c_str()) == 0;
        if (::rename(temporaries[i].c_str(), path.c_str()) != 0) {
            const int error = errno;
            for (size_t j = 0; j < i; ++j) // undo the ones already moved
                if (hadOld[j])
                    ::rename(backups[j].c_str(), images[j].path.c_str());
                else
                    ::unlink(images[j].path.c_str());
            if (hadOld[i]) ::unlink(backups[i].c_str());
            removeAll(temporaries);
            std::string others;
            for (size_t j = 0; j < images.size(); ++j)
                if (j != i) others += (others.empty() ? "" : ", ") + images[j].path;
            throw InputError(path +
                             ": cannot move the finished file into place: " + std::strerror(error) +
                             (others.empty() ? "" : " (so " + others + " was not written either)"));
        }
    }
    for (size_t i = 0; i < images.size(); ++i)
        if (hadOld[i]) ::unlink(backups[i].c_str());
}

void writeImage(const std::string& path, uint32_t width, uint32_t height,
                const std::vector<float>& rgba) {
    writeImages({{path, width, height, &rgba}});
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
