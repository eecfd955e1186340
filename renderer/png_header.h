// A PNG's header against the file's size, before anything is decoded: deflate compresses at most
// 1032:1, so a PNG whose pixels cannot fit in its bytes (128 bytes declaring 16384x16384) is
// refused from its first 29 bytes instead of after seconds and gigabytes of decoding. The image
// readers (image_io.cpp) and the glTF loader's image decoder (gltf_files.cpp) both ask it.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string>

namespace ssgi {

// What is wrong with a PNG of `fileSize` bytes whose first `size` bytes are `bytes`, as "PNG of
// WxH pixels (...), which its N bytes cannot hold ...": "" when nothing is (or when it is not a
// PNG at all, which its decoder says).
inline std::string pngSizeProblem(const unsigned char* bytes, size_t size, uint64_t fileSize) {
    constexpr unsigned char kSignature[] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
    if (size < 29 || std::memcmp(bytes, kSignature, 8) != 0 ||
        std::memcmp(bytes + 12, "IHDR", 4) != 0)
        return "";
    const auto bigEndian = [&](size_t at) {
        return uint64_t(bytes[at]) << 24 | uint64_t(bytes[at + 1]) << 16 |
               uint64_t(bytes[at + 2]) << 8 | uint64_t(bytes[at + 3]);
    };
    const uint64_t width = bigEndian(16), height = bigEndian(20), depth = bytes[24];
    const int colour = bytes[25];
    const uint64_t channels = colour == 0   ? 1
                              : colour == 2 ? 3
                              : colour == 3 ? 1
                              : colour == 4 ? 2
                              : colour == 6 ? 4
                                            : 0;
    if (channels == 0 || depth == 0 || depth > 16) return ""; // the decoder refuses it
    // The decoded bytes, at the least (every row's filter byte left out, which interlacing
    // only adds to); compressed, at least a 1032th of that, the most deflate compresses.
    const uint64_t decoded = height * (width * channels * depth / 8);
    constexpr uint64_t kDeflateMost = 1032;
    if (fileSize >= decoded / kDeflateMost) return "";
    return "PNG of " + std::to_string(width) + "x" + std::to_string(height) + " pixels (" +
           std::to_string(decoded) + " bytes decoded), which its " + std::to_string(fileSize) +
           " bytes cannot hold (deflate compresses at most 1032:1): the file is cut short or "
           "damaged";
}

} // namespace ssgi
