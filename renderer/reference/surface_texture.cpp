#include "reference/surface_texture.h"

#include <algorithm>
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

// Texel index i of an axis of n texels under `wrap`, for any i (also negative).
int wrapped(int i, int n, TextureWrap wrap) {
    switch (wrap) {
    case TextureWrap::ClampToEdge:
        return std::clamp(i, 0, n - 1);
    case TextureWrap::MirroredRepeat: {
        const int period = ((i % (2 * n)) + 2 * n) % (2 * n);
        return period < n ? period : 2 * n - 1 - period;
    }
    default:
        return ((i % n) + n) % n;
    }
}

glm::vec4 texel(const Texture& texture, const TextureSampler& sampler, int x, int y) {
    const int w = int(texture.width), h = int(texture.height);
    x = wrapped(x, w, sampler.wrapU);
    y = wrapped(y, h, sampler.wrapV);
    const uint8_t* p = &texture.rgba[(size_t(y) * size_t(w) + size_t(x)) * 4];
    const auto& decode = srgbToLinear();
    return {decode[p[0]], decode[p[1]], decode[p[2]], float(p[3]) / 255.0f};
}

// The integer base of texel coordinate f, brought near the image while keeping its place in the
// wrap's period (two images for a mirror), so that huge uv values keep their fractional
// precision and the int conversion cannot overflow; a clamp needs no period.
int baseTexel(float f, int n, TextureWrap wrap) {
    if (wrap == TextureWrap::ClampToEdge) return int(std::clamp(f, -1.0f, float(n)));
    const float period = float(wrap == TextureWrap::MirroredRepeat ? 2 * n : n);
    return int(std::fmod(f, period));
}

glm::vec4 sample(const Texture& texture, const TextureSampler& sampler, glm::vec2 uv) {
    const float sx = uv.x * float(texture.width), sy = uv.y * float(texture.height);
    if (!std::isfinite(sx) || !std::isfinite(sy)) return texel(texture, sampler, 0, 0);
    if (sampler.magnifyNearest) {
        const int ix = baseTexel(std::floor(sx), int(texture.width), sampler.wrapU);
        const int iy = baseTexel(std::floor(sy), int(texture.height), sampler.wrapV);
        return texel(texture, sampler, ix, iy);
    }
    // Texel centres sit at half-integer coordinates; uv (0, 0) is the first texel's corner.
    const float fx = sx - 0.5f, fy = sy - 0.5f;
    const float x0 = std::floor(fx), y0 = std::floor(fy);
    const float tx = fx - x0, ty = fy - y0;
    const int ix = baseTexel(x0, int(texture.width), sampler.wrapU);
    const int iy = baseTexel(y0, int(texture.height), sampler.wrapV);
    const glm::vec4 top =
        glm::mix(texel(texture, sampler, ix, iy), texel(texture, sampler, ix + 1, iy), tx);
    const glm::vec4 bottom =
        glm::mix(texel(texture, sampler, ix, iy + 1), texel(texture, sampler, ix + 1, iy + 1), tx);
    return glm::mix(top, bottom, ty);
}

} // namespace

glm::vec4 baseColor(const Material& material, const Texture* texture, glm::vec2 uv,
                    glm::vec4 vertexColor) {
    glm::vec4 color = material.baseColorFactor;
    if (texture && texture->width > 0 && texture->height > 0)
        color *= sample(*texture, material.baseColorSampler, uv);
    return color * vertexColor;
}

bool maskedOut(const Material& material, const Texture* texture, glm::vec2 uv,
               glm::vec4 vertexColor) {
    return material.alphaMask &&
           baseColor(material, texture, uv, vertexColor).a < material.alphaCutoff;
}

} // namespace ssgi::reference
