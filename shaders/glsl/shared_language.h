// How one declaration compiles as both C++ and GLSL (shared.h and the headers it includes):
// in C++, GLSL's vector and matrix types and the functions the shared code calls, from GLM and
// <cmath>, in namespace ssgi::shader; SSGI_CHECK_SIZE (a static_assert in C++, nothing in GLSL),
// SSGI_INLINE and SSGI_OUT (an `out` parameter: a reference in C++).
#ifndef SSGI_SHARED_LANGUAGE_H
#define SSGI_SHARED_LANGUAGE_H

#ifdef __cplusplus
#include <cmath>
#include <glm/glm.hpp>
namespace ssgi::shader {
using vec2 = glm::vec2;
using vec3 = glm::vec3;
using vec4 = glm::vec4;
using mat4 = glm::mat4;
using ivec4 = glm::ivec4;
using uint = glm::uint;
using glm::clamp;
using glm::floatBitsToUint;
using glm::length;
using glm::max;
using glm::mix;
using glm::step;
using glm::uintBitsToFloat;
using std::asinh;
using std::cos;
using std::exp;
using std::floor;
using std::pow;
using std::sin;
using std::sinh;
} // namespace ssgi::shader
#define SSGI_CHECK_SIZE(type, bytes) static_assert(sizeof(type) == bytes, #type " layout")
#define SSGI_INLINE inline
#define SSGI_OUT(type) type&
#else
#define SSGI_CHECK_SIZE(type, bytes)
#define SSGI_INLINE
#define SSGI_OUT(type) out type
#endif

#endif
