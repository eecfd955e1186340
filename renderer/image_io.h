// Image files through OpenImageIO, written whole or not at all (a temporary file renamed into
// place only once it is complete).
#pragma once

#include <string>
#include <vector>

namespace ssgi {

// Writes RGBA float pixels (rows top to bottom). The format follows the extension: .exr keeps
// linear floats (RGB, half), .png stores 8-bit values of the pixels as they are (already
// encoded for display). Throws InputError naming the file on failure.
void writeImage(const std::string& path, uint32_t width, uint32_t height,
                const std::vector<float>& rgba);

// Reads an image as RGBA floats; for tests and comparisons.
std::vector<float> readImage(const std::string& path, uint32_t& width, uint32_t& height);

} // namespace ssgi
