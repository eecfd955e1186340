// tinygltf and stb_image compiled into the fuzz target, so that libFuzzer gets coverage from the
// code that parses most of a malformed glTF and the sanitizers watch it (the Debian shared
// library is neither instrumented nor sanitized).
#define STB_IMAGE_IMPLEMENTATION
#define STB_IMAGE_WRITE_IMPLEMENTATION
#define TINYGLTF_IMPLEMENTATION
#include <tiny_gltf.h>
