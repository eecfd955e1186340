// loadGltf: a glTF read from disk (gltf_files.cpp), its textures, samplers and materials
// converted into the scene's here, then its nodes and meshes (gltf_nodes.cpp, gltf_mesh.cpp).
#include "scene/gltf_loader.h"

#include "scene/gltf_internal.h"

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <tiny_gltf.h>

#include <cmath>
#include <cstring>
#include <map>
#include <sstream>

namespace ssgi {
namespace {

[[noreturn]] void fail(const std::string& file, const std::string& problem) {
    throw InputError(file + ": " + problem);
}

// 8-bit RGBA from whatever the image decoder produced; sRGB bytes are kept as they are because
// the renderer decodes them in the sampler.
Texture convertImage(const tinygltf::Image& image, const std::string& file, size_t index) {
    // An external image is named by its file, which is what a user has to go and look for.
    const bool external = !image.uri.empty() && image.uri.rfind("data:", 0) != 0;
    const std::string what = "image " + std::to_string(index) +
                             (image.name.empty() ? "" : " '" + image.name + "'") +
                             (external ? " (" + image.uri + ")" : "");
    if (image.width <= 0 || image.height <= 0 || image.image.empty())
        fail(file, what + (external ? " is missing or" : "") + " could not be decoded");
    if (image.component < 1 || image.component > 4 || (image.bits != 8 && image.bits != 16))
        fail(file, what + " has " + std::to_string(image.component) + " channels of " +
                       std::to_string(image.bits) + " bits; 1-4 channels of 8 or 16 expected");
    const size_t pixels = size_t(image.width) * size_t(image.height);
    const size_t channels = size_t(image.component), bytesPerChannel = size_t(image.bits) / 8;
    if (image.image.size() != pixels * channels * bytesPerChannel)
        fail(file, what + ": decoded size does not match its dimensions");
    auto channel = [&](size_t pixel, size_t c) -> uint8_t {
        const uint8_t* p = image.image.data() + (pixel * channels + c) * bytesPerChannel;
        if (bytesPerChannel == 1) return *p;
        uint16_t wide;
        std::memcpy(&wide, p, 2);
        return uint8_t((uint32_t(wide) * 255u + 32767u) / 65535u);
    };
    Texture texture;
    texture.name = image.name;
    texture.width = uint32_t(image.width);
    texture.height = uint32_t(image.height);
    texture.rgba.resize(pixels * 4);
    for (size_t i = 0; i < pixels; ++i) {
        uint8_t* out = &texture.rgba[i * 4];
        const bool gray = channels <= 2;
        out[0] = channel(i, 0);
        out[1] = gray ? out[0] : channel(i, 1);
        out[2] = gray ? out[0] : channel(i, 2);
        out[3] = channels == 2 ? channel(i, 1) : channels == 4 ? channel(i, 3) : 255;
    }
    return texture;
}

// Scene texture index for each glTF texture (-1 where it has no usable image). Every texture is
// converted, and an image shared by several textures only once.
std::vector<int> convertTextures(const tinygltf::Model& model, const std::string& file,
                                 Scene& scene, GltfWarnings& warnings) {
    std::map<int, int> sceneTextureOfImage;
    std::vector<int> sceneTextureOf;
    for (size_t t = 0; t < model.textures.size(); ++t) {
        const int image = model.textures[t].source;
        if (image < 0) {
            warnings.once("glTF textures without a PNG or JPEG source are ignored");
            sceneTextureOf.push_back(-1);
            continue;
        }
        if (size_t(image) >= model.images.size())
            fail(file, "texture " + std::to_string(t) + " refers to image " +
                           std::to_string(image) + ", which does not exist");
        auto [it, isNew] = sceneTextureOfImage.try_emplace(image, int(scene.textures.size()));
        if (isNew)
            scene.textures.push_back(
                convertImage(model.images[size_t(image)], file, size_t(image)));
        sceneTextureOf.push_back(it->second);
    }
    return sceneTextureOf;
}

TextureWrap wrapOf(int mode, const std::string& file, const std::string& what) {
    switch (mode) {
    case TINYGLTF_TEXTURE_WRAP_REPEAT:
        return TextureWrap::Repeat;
    case TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE:
        return TextureWrap::ClampToEdge;
    case TINYGLTF_TEXTURE_WRAP_MIRRORED_REPEAT:
        return TextureWrap::MirroredRepeat;
    default:
        fail(file, what + " " + std::to_string(mode) +
                       " is not a glTF wrap mode (10497, 33071 or 33648)");
    }
}

// Whether a glTF filter reads the nearest texel (NEAREST, or a mipmap filter whose texel filter
// is NEAREST) rather than bilinear; undefined filters are bilinear. Without mip maps a mipmap
// filter keeps only its filter within the image.
bool nearestFilter(int filter, bool minification, const std::string& file, const std::string& what,
                   GltfWarnings& warnings) {
    switch (filter) {
    case -1:
    case TINYGLTF_TEXTURE_FILTER_LINEAR:
        return false;
    case TINYGLTF_TEXTURE_FILTER_NEAREST:
        return true;
    case TINYGLTF_TEXTURE_FILTER_NEAREST_MIPMAP_NEAREST:
    case TINYGLTF_TEXTURE_FILTER_LINEAR_MIPMAP_NEAREST:
    case TINYGLTF_TEXTURE_FILTER_NEAREST_MIPMAP_LINEAR:
    case TINYGLTF_TEXTURE_FILTER_LINEAR_MIPMAP_LINEAR:
        if (minification) {
            warnings.once("glTF mipmap filters read the full-size image (there are no mip maps)");
            return filter == TINYGLTF_TEXTURE_FILTER_NEAREST_MIPMAP_NEAREST ||
                   filter == TINYGLTF_TEXTURE_FILTER_NEAREST_MIPMAP_LINEAR;
        }
        [[fallthrough]];
    default:
        fail(file, what + " " + std::to_string(filter) + " is not a glTF " +
                       (minification ? "minification" : "magnification") + " filter");
    }
}

// The sampler of glTF texture `texture` (glTF's default, repeat and bilinear, without one).
TextureSampler samplerOf(const tinygltf::Model& model, int texture, const std::string& file,
                         GltfWarnings& warnings) {
    const int index = model.textures[size_t(texture)].sampler;
    if (index < 0) return {};
    if (size_t(index) >= model.samplers.size())
        fail(file, "texture " + std::to_string(texture) + " refers to sampler " +
                       std::to_string(index) + ", which does not exist");
    const tinygltf::Sampler& source = model.samplers[size_t(index)];
    const std::string what = "sampler " + std::to_string(index);
    TextureSampler sampler;
    sampler.wrapU = wrapOf(source.wrapS, file, what + ": wrapS");
    sampler.wrapV = wrapOf(source.wrapT, file, what + ": wrapT");
    sampler.magnifyNearest =
        nearestFilter(source.magFilter, false, file, what + ": magFilter", warnings);
    sampler.minifyNearest =
        nearestFilter(source.minFilter, true, file, what + ": minFilter", warnings);
    return sampler;
}

void warnAboutIgnoredMaterialData(const tinygltf::Material& material, GltfWarnings& warnings) {
    const auto& pbr = material.pbrMetallicRoughness;
    if (material.normalTexture.index >= 0) warnings.once("glTF normal textures are ignored");
    if (material.occlusionTexture.index >= 0) warnings.once("glTF occlusion textures are ignored");
    bool emissive = material.emissiveTexture.index >= 0;
    for (double e : material.emissiveFactor)
        emissive = emissive || e > 0.0;
    if (emissive) warnings.once("glTF emission is ignored");
    if (pbr.metallicFactor > 0.0 || pbr.metallicRoughnessTexture.index >= 0)
        warnings.once("glTF metallic-roughness data is ignored (every surface is diffuse)");
    if (material.alphaMode == "BLEND") warnings.once("glTF alphaMode BLEND is drawn as OPAQUE");
    if (!material.doubleSided)
        warnings.once("glTF doubleSided false is drawn two-sided (every surface of the scene "
                      "model is)");
    if (pbr.baseColorTexture.index >= 0 && pbr.baseColorTexture.texCoord != 0)
        warnings.once("glTF texCoord sets other than 0 are ignored");
    for (const auto& extension : material.extensions)
        if (extension.first != "KHR_materials_emissive_strength") // said with emission
            warnings.once("glTF material extension " + extension.first + " is ignored");
}

void convertMaterials(const tinygltf::Model& model, const std::string& file,
                      const std::vector<int>& sceneTextureOf, Scene& scene,
                      GltfWarnings& warnings) {
    for (size_t m = 0; m < model.materials.size(); ++m) {
        const tinygltf::Material& source = model.materials[m];
        const auto& pbr = source.pbrMetallicRoughness;
        warnAboutIgnoredMaterialData(source, warnings);
        Material material;
        material.name = source.name;
        if (pbr.baseColorFactor.size() != 4)
            fail(file, "material " + std::to_string(m) + ": baseColorFactor needs 4 numbers");
        for (int c = 0; c < 4; ++c)
            material.baseColorFactor[c] = float(pbr.baseColorFactor[c]);
        // An infinite or negative albedo would fill the image (and every cache) with NaN.
        for (int c = 0; c < 4; ++c)
            if (!(material.baseColorFactor[c] >= 0.0f) || std::isinf(material.baseColorFactor[c]))
                fail(file, "material " + std::to_string(m) +
                               ": baseColorFactor must be finite and not negative");
        for (int c = 0; c < 3; ++c)
            if (material.baseColorFactor[c] > kMaxAlbedo) {
                std::ostringstream what;
                what << "material " << m << ": baseColorFactor " << pbr.baseColorFactor[c]
                     << " is above " << kMaxAlbedo
                     << ": a surface reflects at most the light it receives (scene files refuse "
                        "such an albedo too)";
                fail(file, what.str());
            }
        const int texture = pbr.baseColorTexture.index;
        if (texture >= int(sceneTextureOf.size()))
            fail(file, "material " + std::to_string(m) + " refers to texture " +
                           std::to_string(texture) + ", which does not exist");
        if (texture >= 0) {
            material.baseColorTexture = sceneTextureOf[size_t(texture)];
            material.baseColorSampler = samplerOf(model, texture, file, warnings);
        }
        material.alphaMask = source.alphaMode == "MASK";
        material.alphaCutoff = float(source.alphaCutoff);
        scene.materials.push_back(material);
    }
}

} // namespace

GltfViewpoint loadGltf(const std::string& path, float scale, Scene& scene) {
    const tinygltf::Model model = readGltfModel(path);
    GltfWarnings warnings(path);
    if (!model.skins.empty()) warnings.once("glTF skins are ignored");
    if (!model.animations.empty()) warnings.once("glTF animations are ignored");
    const int firstMaterial = int(scene.materials.size());
    const std::vector<int> sceneTextureOf = convertTextures(model, path, scene, warnings);
    convertMaterials(model, path, sceneTextureOf, scene, warnings);
    return importNodes(model, path, scale, firstMaterial, scene, warnings);
}

} // namespace ssgi
