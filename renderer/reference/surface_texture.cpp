#include "reference/surface_texture.h"

#include <array>
#include <cmath>

namespace ssgi::reference {
namespace {

// Texture bytes are sRGB-encoded; the GPU decodes each texel before filtering, so do we.
const std::array<float, 256>& srgbToLinear() {
    static const std::array<float, 256> table = [] {
        std::array<float, 256> t{};
        for (int i = 0; i < 256; ++i) {
            const float c = float(i) / 255.0f;
            t[size_t(i)] = c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f);
        }
        return t;
    }();
    return table;
}

glm::vec4 texel(const Texture& texture, int x, int y) {
    const int w = int(texture.width), h = int(texture.height);
    x = ((x % w) + w) % w; // repeat wrap, also for negative coordinates
    y = ((y % h) + h) % h;
    const uint8_t* p = &texture.rgba[(size_t(y) * size_t(w) + size_t(x)) * 4];
    const auto& decode = srgbToLinear();
    return {decode[p[0]], decode[p[1]], decode[p[2]], float(p[3]) / 255.0f};
}

glm::vec4 bilinear(const Texture& texture, glm::vec2 uv) {
    // Texel centres sit at half-integer coordinates; uv (0, 0) is the first texel's corner.
    const float fx = uv.x * float(texture.width) - 0.5f;
    const float fy = uv.y * float(texture.height) - 0.5f;
    if (!std::isfinite(fx) || !std::isfinite(fy)) return texel(texture, 0, 0);
    const float x0 = std::floor(fx), y0 = std::floor(fy);
    const float tx = fx - x0, ty = fy - y0;
    // Wrap the integer base first so that huge uv values keep their fractional precision.
    const int ix = int(std::fmod(x0, float(texture.width)));
    const int iy = int(std::fmod(y0, float(texture.height)));
    const glm::vec4 top = glm::mix(texel(texture, ix, iy), texel(texture, ix + 1, iy), tx);
    const glm::vec4 bottom =
        glm::mix(texel(texture, ix, iy + 1), texel(texture, ix + 1, iy + 1), tx);
    return glm::mix(top, bottom, ty);
}

} // namespace

glm::vec4 baseColor(const Material& material, const Texture* texture, glm::vec2 uv) {
    glm::vec4 color = material.baseColorFactor;
    if (texture && texture->width > 0 && texture->height > 0) color *= bilinear(*texture, uv);
    return color;
}

bool maskedOut(const Material& material, const Texture* texture, glm::vec2 uv) {
    return material.alphaMask && baseColor(material, texture, uv).a < material.alphaCutoff;
}

} // namespace ssgi::reference
