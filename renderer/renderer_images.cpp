// What a program reads of the renderer's last frame: its images by name, a cache's count beside
// the shared positions, the viewer's copy source, the cached effects and their refresh tiles.
#include "renderer.h"

#include "shared.h"

#include <bit>
#include <cmath>
#include <cstring>

namespace ssgi {

graph::ImageRef Renderer::imageNamed(const std::string& name) const {
    using graph::FrameGraph;
    // After the frame every pair has swapped: what it wrote is now the "previous" side.
    const CacheSet& caches = build_->caches;
    if (caches.viewDepthHistory && name == "gbuffer.view_depth")
        return FrameGraph::previous(*caches.viewDepthHistory);
    for (const EffectCache& cache : caches.effects) {
        if (name == cache.name() + ".history") return FrameGraph::previous(cache.valueHistory);
        if (name == cache.name() + ".count") return FrameGraph::previous(cache.countHistory);
    }
    return graph_->find(name);
}

const EffectCache* Renderer::metaOf(const std::string& name) const {
    for (const EffectCache& cache : build_->caches.effects)
        if (name == cache.name() + ".meta") return &cache;
    return nullptr;
}

std::vector<float> Renderer::readImage(const std::string& name) {
    if (name == "gbuffer.position") { // as gbuffer_position.glsl and pixel_to_world.glsl do
        std::vector<float> position = readImage("gbuffer.view_depth");
        const VkRect2D output = build_->output();
        const glm::mat4& toWorld = previousPixelToWorld_; // the last frame's
        for (uint32_t y = 0; y < output.extent.height; ++y)
            for (uint32_t x = 0; x < output.extent.width; ++x) {
                float* p = &position[4 * (size_t(y) * output.extent.width + x)];
                const float depth = p[0];
                const glm::vec2 centre(float(x + output.offset.x) + 0.5f,
                                       float(y + output.offset.y) + 0.5f);
                const glm::vec3 ray = glm::vec3(toWorld[0]) * centre.x +
                                      glm::vec3(toWorld[1]) * centre.y + glm::vec3(toWorld[2]);
                const glm::vec3 world = glm::vec3(toWorld[3]) + ray * depth;
                const glm::vec4 value = depth == 0.0f ? glm::vec4(0.0f) : glm::vec4(world, 1.0f);
                std::memcpy(p, &value, sizeof(value));
            }
        return position;
    }
    if (const EffectCache* cache = metaOf(name)) { // the shared positions, the count in alpha
        std::vector<float> meta = readImage("gbuffer.position");
        const std::vector<float> count = readImage(cache->name() + ".count");
        for (size_t i = 0; i < meta.size(); i += 4)
            meta[i + 3] = count[i];
        return meta;
    }
    const graph::ImageRef ref = imageNamed(name);
    if (!ref.valid()) throw InputError("no image named '" + name + "' in the frame");
    if (name == "rsm.vpls") return readRsmVpls(ref);
    if (name == "hdr") return readHdr(ref);
    // A screen image is read where the output lies in it: its guard band left out.
    const VkExtent2D e = graph_->image(ref).extent;
    const bool screen = e.width == build_->size.width && e.height == build_->size.height;
    if (name == "reprojection")
        return readReprojection(ref, screen ? std::optional(build_->output()) : std::nullopt);
    std::vector<float> texels =
        graph_->download(ref, screen ? std::optional(build_->output()) : std::nullopt);
    // A scalar effect's value (one half float, SCALAR_SKIPPED where skipped) as RGB + computed.
    if (graph_->image(ref).format == kScalarValueFormat)
        for (size_t i = 0; i < texels.size(); i += 4) {
            const float value = texels[i];
            const bool skipped = value == kScalarSkipped;
            texels[i] = texels[i + 1] = texels[i + 2] = skipped ? 0.0f : value;
            texels[i + 3] = skipped ? 0.0f : 1.0f;
        }
    for (const EffectCache& cache : build_->caches.effects) {
        if (cache.effect.scalar &&
            name == cache.name() + ".history") // RG (value, blur) as RGB + blur
            for (size_t i = 0; i < texels.size(); i += 4) {
                const float value = texels[i], blur = texels[i + 1];
                texels[i + 1] = texels[i + 2] = value;
                texels[i + 3] = blur;
            }
        if (name == cache.name() + ".count") // the count, and whether it is due (1) or not (0)
            for (size_t i = 0; i < texels.size(); i += 4) {
                const CountTexel t = unpackCount(uint8_t(std::lround(texels[i] * 255.0f)));
                texels[i] = t.count;
                texels[i + 1] = t.due ? 1.0f : 0.0f;
            }
    }
    return texels;
}

// The RSM's VPL texels (rsm_vpl.glsl): flux = albedo x light colour x share, the albedo's
// channels square roots in 10 bits; the distance along the light's axis in alpha.
std::vector<float> Renderer::readRsmVpls(graph::ImageRef ref) {
    const std::vector<uint8_t> bytes = graph_->readTexels(ref);
    std::vector<float> texels(bytes.size() / sizeof(uint32_t));
    for (size_t i = 0; i < texels.size(); i += 4) {
        uint32_t t[4];
        std::memcpy(t, &bytes[4 * i], sizeof(t));
        float share = 0.0f, axisDepth = 0.0f;
        std::memcpy(&share, &t[1], sizeof(float));
        std::memcpy(&axisDepth, &t[3], sizeof(float));
        for (int c = 0; c < 3; ++c) {
            const float root = float((t[0] >> (10 * c)) & 1023u) / 1023.0f;
            texels[i + c] = root * root * lastLightColor_[c] * share;
        }
        texels[i + 3] = axisDepth;
    }
    return texels;
}

// The composite's HDR output: three 21-bit floats in two words (shared.h hdrBits,
// composite.comp packHdr), alpha 1.
std::vector<float> Renderer::readHdr(graph::ImageRef ref) {
    const std::vector<uint8_t> bytes = graph_->readTexels(ref);
    std::vector<float> texels(bytes.size() / sizeof(uint32_t) * 2);
    for (size_t i = 0; i < texels.size(); i += 4) {
        uint32_t t[2];
        std::memcpy(t, &bytes[2 * i], sizeof(t));
        constexpr uint32_t bits21 = (1u << 21) - 1u;
        texels[i] = shader::hdrValue(t[0] & bits21);
        texels[i + 1] = shader::hdrValue(((t[0] >> 21) | (t[1] << 11)) & bits21);
        texels[i + 2] = shader::hdrValue((t[1] >> 10) & bits21);
        texels[i + 3] = 1.0f;
    }
    return texels;
}

// The reprojection pass's texels (shared_cache.h REPROJECTION_*): where each pixel's surface lay in
// last frame's image, in its texels (x, y), the offset of the texel that holds it from the
// nearest one ((dx + 1) + 3 (dy + 1); -1 where none does) and the bilinear footprint's bits. The
// whole texels follow from the pixel's world position, as reprojection.glsl unpacks them.
std::vector<float> Renderer::readReprojection(graph::ImageRef ref, std::optional<VkRect2D> area) {
    const std::vector<uint8_t> bytes = graph_->readTexels(ref, area);
    const size_t count = bytes.size() / sizeof(uint32_t);
    const std::vector<float> position =
        area ? readImage("gbuffer.position") : std::vector<float>(4 * count, 0.0f);
    const glm::vec2 size(float(build_->size.width), float(build_->size.height));
    constexpr uint32_t fractionMask = (1u << REPROJECTION_FRACTION_BITS) - 1u;
    std::vector<float> texels(4 * count);
    for (size_t i = 0; i < count; ++i) {
        uint32_t t = 0;
        std::memcpy(&t, &bytes[4 * i], sizeof(t));
        const int offset = int((t >> REPROJECTION_OFFSET_SHIFT) & 15u) - 1;
        float* out = &texels[4 * i];
        out[2] = float(offset); // -1: not found
        out[3] = float((t >> REPROJECTION_FOOTPRINT_SHIFT) & 15u);
        if (offset < 0) continue;
        const float* world = &position[4 * i];
        const glm::vec4 clip = reprojectedInto_ * glm::vec4(world[0], world[1], world[2], 1.0f);
        const glm::vec2 projected = (glm::vec2(clip) / clip.w * 0.5f + 0.5f) * size;
        const glm::vec2 fraction =
            glm::vec2(float(t & fractionMask),
                      float((t >> REPROJECTION_FRACTION_BITS) & fractionMask)) /
            float(REPROJECTION_SUBTEXEL);
        const glm::vec2 point = glm::round(projected - fraction) + fraction;
        out[0] = point.x;
        out[1] = point.y;
    }
    return texels;
}

bool Renderer::hasImage(const std::string& name) const {
    if (name == "gbuffer.position") return true;
    return metaOf(name) || imageNamed(name).valid();
}

const vk::Image& Renderer::prepareCopySource(VkCommandBuffer cmd, const std::string& name) {
    const graph::ImageRef ref = imageNamed(name);
    if (!ref.valid()) throw InputError("no image named '" + name + "' in the frame");
    return graph_->prepareTransferSource(cmd, ref);
}

std::vector<std::string> Renderer::cachedEffects() const {
    std::vector<std::string> names;
    for (const EffectCache& cache : build_->caches.effects)
        names.push_back(cache.name());
    return names;
}

VkRect2D Renderer::refreshedTile(const std::string& effect) const {
    for (const EffectCache& cache : build_->caches.effects) {
        if (cache.name() != effect || !cache.refresh || cache.slot >= lastFrame_.effects.size())
            continue;
        const int index = lastFrame_.effects[cache.slot].refreshTile;
        if (index < 0) continue;
        const TileRect tile = cache.refresh->rect(uint32_t(index));
        // In the output's pixels: the tile less what of it lies in the guard band.
        const VkRect2D v = build_->output();
        const int32_t x0 = std::max(int32_t(tile.x), v.offset.x);
        const int32_t y0 = std::max(int32_t(tile.y), v.offset.y);
        const int32_t x1 =
            std::min(int32_t(tile.x + tile.width), v.offset.x + int32_t(v.extent.width));
        const int32_t y1 =
            std::min(int32_t(tile.y + tile.height), v.offset.y + int32_t(v.extent.height));
        if (x1 <= x0 || y1 <= y0) return {};
        return {{x0 - v.offset.x, y0 - v.offset.y}, {uint32_t(x1 - x0), uint32_t(y1 - y0)}};
    }
    return {};
}

std::optional<Renderer::WorldCacheCounts> Renderer::worldCacheCounts() {
    if (frameIndex_ == 0 || !hasImage("world.stats")) return std::nullopt;
    const std::vector<float> stats = readImage("world.stats"); // WORLD_STATS x 2, RGBA each
    const size_t row = size_t((patternFrame() - 1) & 1u) * WORLD_STATS;
    auto at = [&](int stat) { return std::bit_cast<uint32_t>(stats[4 * (row + size_t(stat))]); };
    WorldCacheCounts c;
    c.live = at(WORLD_STAT_LIVE);
    c.filled = at(WORLD_STAT_NEW);
    c.refreshed = at(WORLD_STAT_REFRESHED);
    c.evicted = at(WORLD_STAT_EVICTED);
    c.full = at(WORLD_STAT_FULL);
    c.edges = at(WORLD_STAT_EDGES);
    c.cut = at(WORLD_STAT_CUT);
    const VkExtent2D table = graph_->image(imageNamed("world.keys")).extent;
    c.entries = table.width * table.height;
    return c;
}

} // namespace ssgi
