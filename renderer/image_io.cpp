#include "image_io.h"

#include "atomic_file.h"
#include "png_header.h"
#include "scene/scene.h"

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <memory>
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

// One image encoded in memory, as its file will hold it; throws (writing nothing) on failure.
std::string encode(const ImageFile& image) {
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
    std::vector<unsigned char> bytes;
    OIIO::Filesystem::IOVecOutput memory(bytes);
    if (!out->supports("ioproxy") || !out->set_ioproxy(&memory))
        throw std::runtime_error(path + ": OpenImageIO cannot write this format to memory");
    const int channels = exr ? 3 : 4;
    OIIO::ImageSpec spec(int(image.width), int(image.height), channels,
                         !exr       ? OIIO::TypeDesc::UINT8
                         : fitsHalf ? OIIO::TypeDesc::HALF
                                    : OIIO::TypeDesc::FLOAT);
    if (exr) {
        spec.attribute("compression", "zip");
        for (const auto& [name, value] : image.attributes.ints)
            spec.attribute(name, value);
        for (const auto& [name, value] : image.attributes.floats)
            spec.attribute(name, value);
        for (const auto& [name, value] : image.attributes.texts)
            spec.attribute(name, value);
    }
    // The values as given: OpenImageIO would otherwise divide a PNG's colour by its alpha, which
    // readImage (the colour as stored) would not undo.
    spec.attribute("oiio:UnassociatedAlpha", 1);
    if (!out->open(path, spec) || !out->write_image(OIIO::TypeDesc::FLOAT, values.data()) ||
        !out->close())
        throw InputError(path + ": encoding failed: " + out->geterror());
    return std::string(bytes.begin(), bytes.end());
}

// OpenEXR (3.1) allocates each header attribute's declared size before it reads the value: a
// 53-byte file declaring a 1.8 GB string took that much memory, and an unknown attribute type
// of a few hundred MB took seconds to refuse (fuzz_image). The header is walked here first
// (magic, version, then per part `name\0 type\0 int32 size, value`, each part ending in \0),
// and a size that is negative or runs past the end of the file is refused before OpenEXR
// sees the file. Throws InputError; returns quietly on what OpenEXR itself should judge.
void checkExrHeader(const std::string& path, uint64_t fileSize) {
    std::ifstream in(path, std::ios::binary);
    const auto fail = [&](const std::string& why) {
        throw InputError(path + ": not a readable OpenEXR file: " + why);
    };
    unsigned char start[8];
    if (!in.read(reinterpret_cast<char*>(start), 8)) fail("shorter than its 8-byte start");
    if (start[0] != 0x76 || start[1] != 0x2f || start[2] != 0x31 || start[3] != 0x01)
        return; // not OpenEXR's magic number: OpenEXR says so
    const bool multipart = (start[5] & 0x10) != 0;
    // A name or type name: at most 255 characters and a \0 (31 without the long-names flag;
    // OpenEXR checks that).
    const auto readName = [&](std::string& name) {
        name.clear();
        for (char c; in.get(c);) {
            if (c == '\0') return true;
            if (name.size() == 255) return false;
            name.push_back(c);
        }
        return false;
    };
    std::string name, type;
    for (int part = 0;; ++part) {
        for (;;) {
            if (!readName(name)) fail("a header attribute's name runs past 255 bytes or the file");
            if (name.empty()) break; // the end of this part's header
            if (!readName(type)) fail("attribute '" + name + "' has no type name");
            unsigned char bytes[4];
            if (!in.read(reinterpret_cast<char*>(bytes), 4))
                fail("attribute '" + name + "' has no size");
            const int32_t size = int32_t(uint32_t(bytes[0]) | uint32_t(bytes[1]) << 8 |
                                         uint32_t(bytes[2]) << 16 | uint32_t(bytes[3]) << 24);
            const uint64_t at = uint64_t(in.tellg());
            if (size < 0 || uint64_t(size) > fileSize - at)
                fail("attribute '" + name + "' (" + type + ") declares " + std::to_string(size) +
                     " bytes, and " + std::to_string(fileSize - at) + " are left in the file");
            in.seekg(size, std::ios::cur);
        }
        // A multi-part file lists its parts' headers one after another, then an empty one.
        if (!multipart || in.peek() == 0 || in.peek() == std::char_traits<char>::eof()) return;
        if (part > 100000) fail("more than 100000 parts");
    }
}

} // namespace

void writeImages(const std::vector<ImageFile>& images) {
    std::vector<FileBytes> files;
    for (const ImageFile& image : images) {
        const std::string ext = fs::path(image.path).extension().string();
        if (ext != ".exr" && ext != ".png")
            throw InputError(image.path + ": output must end in .png or .exr");
        // What readImage reads, nothing larger: a file written here is one it takes back.
        if (image.width < 1 || image.height < 1 || image.width > uint32_t(kMaxImageSide) ||
            image.height > uint32_t(kMaxImageSide))
            throw InputError(image.path + ": " + std::to_string(image.width) + "x" +
                             std::to_string(image.height) + " pixels; images of 1.." +
                             std::to_string(kMaxImageSide) + " pixels a side are written");
        if (!image.rgba || image.rgba->size() != size_t(image.width) * image.height * 4)
            throw InputError(image.path + ": " +
                             std::to_string(image.rgba ? image.rgba->size() : 0) +
                             " values given for " + std::to_string(image.width) + "x" +
                             std::to_string(image.height) + " RGBA pixels");
    }
    for (const ImageFile& image : images)
        files.push_back({image.path, encode(image)});
    writeFilesAtomically(files);
}

void writeImage(const std::string& path, uint32_t width, uint32_t height,
                const std::vector<float>& rgba) {
    writeImages({{path, width, height, &rgba}});
}

std::vector<float> readImage(const std::string& path, uint32_t& width, uint32_t& height,
                             ImageAttributes* attributes) {
    // Looked at before it is opened: a FIFO would block the reader, a device never end.
    struct stat status {};
    if (::stat(path.c_str(), &status) != 0)
        throw InputError(path + ": cannot read image: " + std::strerror(errno));
    if (!S_ISREG(status.st_mode)) throw InputError(path + ": not a regular file");
    // The colour as stored: OpenImageIO would otherwise multiply a PNG's colour by its alpha.
    OIIO::ImageSpec config;
    config.attribute("oiio:UnassociatedAlpha", 1);
    // A .png is read by the PNG reader only and an .exr by the OpenEXR reader only: when the
    // named reader refuses a file, ImageInput::open hands it to every other format it has
    // (LibRaw and the rest), so a damaged .png reached every parser and an EXR named .png was
    // read as linear radiance and compared as a display image. Other names are left to open.
    std::string extension = fs::path(path).extension().string();
    std::transform(extension.begin(), extension.end(), extension.begin(),
                   [](unsigned char c) { return char(std::tolower(c)); });
    const char* format = extension == ".png" ? "png" : extension == ".exr" ? "openexr" : nullptr;
    std::unique_ptr<OIIO::ImageInput> in;
    if (format) {
        if (extension == ".exr") checkExrHeader(path, uint64_t(status.st_size));
        in = OIIO::ImageInput::create(format);
        if (!in) throw InputError(path + ": cannot read image: " + OIIO::geterror());
        OIIO::ImageSpec opened;
        if (!in->open(path, opened, config)) {
            const std::string why = in->geterror();
            throw InputError(path + ": not a readable " +
                             (extension == ".png" ? "PNG" : "OpenEXR") + " file" +
                             (why.empty() ? "" : ": " + why));
        }
    } else {
        in = OIIO::ImageInput::open(path, &config);
        if (!in) throw InputError(path + ": cannot read image: " + OIIO::geterror());
    }
    const OIIO::ImageSpec& spec = in->spec();
    if (spec.width < 1 || spec.height < 1 || spec.depth != 1 || spec.width > kMaxImageSide ||
        spec.height > kMaxImageSide)
        throw InputError(path + ": declares " + std::to_string(spec.width) + "x" +
                         std::to_string(spec.height) + " pixels; images of 1.." +
                         std::to_string(kMaxImageSide) + " pixels a side are read");
    // A PNG whose bytes cannot hold the pixels it declares: before they take memory and time.
    if (extension == ".png") {
        unsigned char start[29] = {};
        std::ifstream file(path, std::ios::binary);
        file.read(reinterpret_cast<char*>(start), sizeof start);
        const std::string problem =
            pngSizeProblem(start, size_t(file.gcount()), uint64_t(status.st_size));
        if (!problem.empty()) throw InputError(path + ": a " + problem);
    }
    // Which of the file's channels holds R, G, B and A (-1: none; alpha is then 1). By name, never
    // by position: X, Y, Z or a layer's normal.X read as RGB would pass any comparison with
    // another file of the same kind.
    const int n = spec.nchannels;
    const auto& names = spec.channelnames;
    const auto channel = [&](const char* name) {
        const auto it = std::find(names.begin(), names.end(), name);
        return it == names.end() ? -1 : int(it - names.begin());
    };
    const int r = channel("R"), g = channel("G"), b = channel("B"), a = channel("A"),
              y = channel("Y");
    std::array<int, 4> source{};
    if (r >= 0 && g >= 0 && b >= 0)
        source = {r, g, b, a};
    else if (r < 0 && g < 0 && b < 0 && y >= 0 && n == (a >= 0 ? 2 : 1))
        source = {y, y, y, a}; // grey stands for the same value in R, G and B
    else {
        std::string found;
        for (const std::string& name : names)
            found += (found.empty() ? "" : ", ") + name;
        throw InputError(path + ": holds the channels " + (found.empty() ? "(none)" : found) +
                         "; an image with channels R, G, B (and A), or Y (and A) alone, is read");
    }
    width = uint32_t(spec.width);
    height = uint32_t(spec.height);
    const size_t pixelCount = size_t(width) * height;
    const int used = source[3] >= 0 ? 4 : 3;
    const int first = *std::min_element(source.begin(), source.begin() + used);
    const int last = *std::max_element(source.begin(), source.begin() + used);
    // The channels from the first to the last needed at once where that is at most four (the
    // usual order), else each on its own, so that memory never grows with unneeded channels.
    const bool together = last - first < 4;
    const size_t stride = together ? size_t(last - first + 1) : 1;
    std::vector<float> pixels, rgba;
    try {
        pixels.resize(pixelCount * stride);
        rgba.assign(pixelCount * 4, 1.0f);
    } catch (const std::bad_alloc&) {
        throw InputError(path + ": " + std::to_string(width) + "x" + std::to_string(height) +
                         " pixels do not fit in memory");
    }
    const auto read = [&](int begin, int end) {
        if (!in->read_image(0, 0, begin, end, OIIO::TypeDesc::FLOAT, pixels.data()))
            throw InputError(path + ": " + in->geterror());
    };
    if (together) read(first, last + 1);
    for (int c = 0; c < used; ++c) {
        if (!together) read(source[size_t(c)], source[size_t(c)] + 1);
        const size_t offset = together ? size_t(source[size_t(c)] - first) : 0;
        for (size_t i = 0; i < pixelCount; ++i)
            rgba[4 * i + size_t(c)] = pixels[stride * i + offset];
    }
    if (attributes) {
        for (const OIIO::ParamValue& p : spec.extra_attribs) {
            if (p.nvalues() != 1) continue;
            if (p.type() == OIIO::TypeDesc::INT)
                attributes->ints[p.name().string()] = p.get_int();
            else if (p.type() == OIIO::TypeDesc::FLOAT)
                attributes->floats[p.name().string()] = p.get_float();
            else if (p.type() == OIIO::TypeDesc::STRING)
                attributes->texts[p.name().string()] = p.get_string();
        }
    }
    return rgba;
}

} // namespace ssgi
