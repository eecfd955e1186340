// The Lambertian albedo and alpha of a material at a texture coordinate, exactly as the
// G-buffer reads them: baseColorFactor times the sRGB-decoded texture, bilinear, repeat wrap.
#pragma once

#include "scene/scene.h"

namespace ssgi::reference {

// rgb: linear albedo; a: coverage for the alpha mask. `texture` may be null (no texture).
glm::vec4 baseColor(const Material& material, const Texture* texture, glm::vec2 uv);

// True where the alpha mask cuts the surface away (glTF MASK: alpha below the cutoff).
bool maskedOut(const Material& material, const Texture* texture, glm::vec2 uv);

} // namespace ssgi::reference
