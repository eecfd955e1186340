// The SPIR-V of every shader in shaders/glsl, compiled at build time and embedded in the program
// (CMakeLists.txt generates the table), so that a program finds its shaders wherever it is
// installed.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace ssgi::vk {

struct EmbeddedShader {
    const char* name; // the source's file name: "ao.comp", "gbuffer.vert"
    const uint32_t* code;
    size_t bytes;
};

const std::vector<EmbeddedShader>& embeddedShaders();

} // namespace ssgi::vk
