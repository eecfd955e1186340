// Image files through OpenImageIO, written whole or not at all (a temporary file renamed into
// place only once it is complete).
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace ssgi {

// Writes RGBA float pixels (rows top to bottom). The format follows the extension: .exr keeps
// linear floats (RGB, half, or 32-bit floats where a value exceeds half's 65504), .png stores
// 8-bit values of the pixels as they are (already encoded for display). Throws InputError
// naming the file on failure, std::runtime_error (a renderer's failure) when a value is NaN or
// infinite; either way nothing is written.
void writeImage(const std::string& path, uint32_t width, uint32_t height,
                const std::vector<float>& rgba);

// Attributes an .exr's header carries beside its pixels, by OpenImageIO name (e.g. "ssgi:noise"):
// typed as the header stores them. A .png carries none.
struct ImageAttributes {
    std::map<std::string, int> ints;
    std::map<std::string, float> floats;
    std::map<std::string, std::string> texts;
};

struct ImageFile {
    std::string path;
    uint32_t width = 0, height = 0;
    const std::vector<float>* rgba = nullptr;
    ImageAttributes attributes; // written into an .exr's header
};
// Writes several images as one: all of them land, or none does (what was at their paths before
// stays), as writeImage says for each.
void writeImages(const std::vector<ImageFile>& images);

// The largest side of an image that readImage takes: the programs' own largest output.
constexpr int kMaxImageSide = 16384;

// Reads an image as RGBA floats, the colour as the file stores it (a PNG's colour is not
// multiplied by its alpha). Channels are taken by name: R, G, B (and A) as the colour; a grey
// image, Y (and A) and nothing else, gives R = G = B; alpha is 1 where the file has none; other
// channels beside R, G, B (a depth Z) are not read. A .png is read as a PNG only and an .exr as
// an OpenEXR only (an EXR's header is checked first: no attribute may declare more bytes than
// the file holds); other names as OpenImageIO finds them. InputError for anything else: a file
// that is not a regular file or not what its name says, a size beyond kMaxImageSide or beyond
// memory, channels that are neither R, G, B nor grey (X, Y, Z; R, G; layers such as
// normal.X), the message naming the channels found. `attributes`, when given, gets the header's
// int, float and string attributes.
std::vector<float> readImage(const std::string& path, uint32_t& width, uint32_t& height,
                             ImageAttributes* attributes = nullptr);

} // namespace ssgi
