// The Lambertian albedo and alpha of a material at a texture coordinate, as the G-buffer reads
// them: baseColorFactor times the sRGB-decoded texture, filtered and wrapped as the material's
// sampler says, times the vertex colour. A path tracer's lookup has no footprint to choose
// between the minification and the magnification filter: it takes the magnification filter.
#pragma once

#include "scene/scene.h"

namespace ssgi::reference {

// rgb: linear albedo; a: coverage for the alpha mask. `texture` may be null (no texture);
// `vertexColor` is the interpolated Vertex::color over 65535, 1 where the mesh has none.
glm::vec4 baseColor(const Material& material, const Texture* texture, glm::vec2 uv,
                    glm::vec4 vertexColor = glm::vec4(1.0f));

// True where the alpha mask cuts the surface away (glTF MASK: alpha below the cutoff).
bool maskedOut(const Material& material, const Texture* texture, glm::vec2 uv,
               glm::vec4 vertexColor = glm::vec4(1.0f));

} // namespace ssgi::reference
