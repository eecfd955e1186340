// The checks of a glTF's JSON that tinygltf does not make, or makes with a message that says the
// wrong thing (gltf_internal.h checkGltfJsonFirst, checkGltfJson): the extension lists and a
// buffer view's byteStride before tinygltf reads the file, then every value tinygltf would take
// without a word (a wrong kind, a fraction, an index below zero) and the extensions the loader
// does not read.
#include "scene/gltf_internal.h"

#include <nlohmann/json.hpp>

#include <cmath>
#include <cstring>
#include <string>

namespace ssgi {

namespace {

[[noreturn]] void fail(const std::string& file, const std::string& problem) {
    throw InputError(file + ": " + problem);
}

} // namespace

// The JSON of a .gltf, or of a .glb's JSON chunk (when the container holds one); null when it is
// not JSON (tinygltf says why).
nlohmann::json gltfJson(const std::string& bytes, bool binary) {
    std::string text = bytes;
    if (binary) {
        uint32_t length = 0;
        if (bytes.size() < 20) return nullptr;
        std::memcpy(&length, bytes.data() + 12, 4);
        if (length > bytes.size() - 20) return nullptr;
        text = bytes.substr(20, length);
    }
    return nlohmann::json::parse(text, nullptr, false);
}

// What tinygltf refuses with a message that says the wrong thing, or reads against the
// specification, checked before it reads the file: a buffer view's byteStride (its message
// said "must be a multiple of 4" of 256, a multiple of 4), and extensionsRequired or
// extensionsUsed that are not arrays of names (tinygltf skipped them, so an extension the file
// requires was never refused).
void checkGltfJsonFirst(const std::string& path, const nlohmann::json& root) {
    if (!root.is_object()) return;
    for (const char* key : {"extensionsRequired", "extensionsUsed"}) {
        if (!root.contains(key)) continue;
        const nlohmann::json& names = root[key];
        bool strings = names.is_array();
        for (size_t i = 0; strings && i < names.size(); ++i)
            strings = names[i].is_string();
        if (!strings) {
            std::string shown = names.dump();
            if (shown.size() > 60) shown = shown.substr(0, 60) + "...";
            fail(path, std::string(key) + " is " + shown +
                           ", not an array of extension names (strings), as glTF requires");
        }
    }
    if (!root.contains("bufferViews") || !root["bufferViews"].is_array()) return;
    size_t i = 0;
    for (const nlohmann::json& view : root["bufferViews"]) {
        const std::string what = "buffer view " + std::to_string(i++);
        if (!view.is_object() || !view.contains("byteStride")) continue;
        const nlohmann::json& stride = view["byteStride"];
        if (!stride.is_number() || stride.get<double>() != std::floor(stride.get<double>()))
            fail(path, what + ": byteStride " + stride.dump() +
                           " is not a whole number (glTF allows multiples of 4 from 4 to 252)");
        const double value = stride.get<double>();
        const std::string shown = stride.dump();
        if (value > 252)
            fail(path, what + ": byteStride " + shown +
                           " is more than 252, the largest glTF allows (multiples of 4 from 4 "
                           "to 252)");
        if (value < 4)
            fail(path, what + ": byteStride " + shown +
                           " is less than 4, the smallest glTF allows (multiples of 4 from 4 to "
                           "252)");
        if (std::fmod(value, 4.0) != 0.0)
            fail(path, what + ": byteStride " + shown +
                           " is not a multiple of 4 (glTF allows multiples of 4 from 4 to 252)");
    }
}

// What tinygltf reads without a word: a value of the wrong kind is taken as its default (a wrap
// mode written as "CLAMP_TO_EDGE" became REPEAT), a fraction or a number beyond 32 bits is cut
// to an int, and an index below zero means "none". The file's JSON is checked here for those,
// and every extension it uses that the loader does not read is named once.
void checkGltfJson(const std::string& path, const nlohmann::json& root, GltfWarnings& warnings) {
    if (!root.is_object()) return; // tinygltf read it; nothing more to say here
    const auto isIndex = [](const nlohmann::json& v) {
        return (v.is_number_integer() || v.is_number_unsigned()) && v.get<double>() >= 0 &&
               v.get<double>() <= 2147483647.0;
    };
    const auto index = [&](const nlohmann::json& object, const char* key, const std::string& what) {
        if (!object.is_object() || !object.contains(key)) return;
        const nlohmann::json& v = object[key];
        if (!isIndex(v))
            fail(path, what + ": " + key + " " + v.dump() + " is not an index (0 or more)");
    };
    const auto integer = [&](const nlohmann::json& object, const char* key, const std::string& what,
                             const char* kind) {
        if (!object.is_object() || !object.contains(key)) return;
        const nlohmann::json& v = object[key];
        if (!(v.is_number_integer() || v.is_number_unsigned()) ||
            std::fabs(v.get<double>()) > 2147483647.0)
            fail(path, what + ": " + key + " " + v.dump() + " is not a glTF " + kind +
                           " (a whole number)");
    };
    const auto array = [&](const char* key) {
        static const nlohmann::json empty = nlohmann::json::array();
        return root.contains(key) && root[key].is_array() ? root[key] : empty;
    };
    size_t i = 0;
    for (const nlohmann::json& sampler : array("samplers")) {
        const std::string what = "sampler " + std::to_string(i++);
        integer(sampler, "wrapS", what, "wrap mode");
        integer(sampler, "wrapT", what, "wrap mode");
        integer(sampler, "magFilter", what, "magnification filter");
        integer(sampler, "minFilter", what, "minification filter");
    }
    i = 0;
    for (const nlohmann::json& texture : array("textures")) {
        const std::string what = "texture " + std::to_string(i++);
        index(texture, "sampler", what);
        index(texture, "source", what);
    }
    i = 0;
    for (const nlohmann::json& material : array("materials")) {
        const std::string what = "material " + std::to_string(i++);
        if (!material.is_object()) continue;
        if (material.contains("alphaMode")) {
            const nlohmann::json& mode = material["alphaMode"];
            if (!mode.is_string() || (mode != "OPAQUE" && mode != "MASK" && mode != "BLEND"))
                fail(path, what + ": alphaMode " + mode.dump() + " is not OPAQUE, MASK or BLEND");
        }
        // Its texture references: baseColorTexture (in pbrMetallicRoughness), normalTexture, ...
        std::vector<const nlohmann::json*> holders = {&material};
        if (material.contains("pbrMetallicRoughness"))
            holders.push_back(&material["pbrMetallicRoughness"]);
        for (const nlohmann::json* holder : holders) {
            if (!holder->is_object()) continue;
            for (const auto& [key, info] : holder->items())
                if (key.size() > 7 && key.compare(key.size() - 7, 7, "Texture") == 0) {
                    index(info, "index", what + " " + key);
                    index(info, "texCoord", what + " " + key);
                }
        }
    }
    // The other references between objects, and the primitives' modes.
    index(root, "scene", "the file");
    const auto indexList = [&](const nlohmann::json& object, const char* key,
                               const std::string& what) {
        if (!object.is_object() || !object.contains(key) || !object[key].is_array()) return;
        for (const nlohmann::json& v : object[key])
            if (!isIndex(v))
                fail(path, what + ": " + key + " holds " + v.dump() + ", not an index (0 or more)");
    };
    i = 0;
    for (const nlohmann::json& scene : array("scenes"))
        indexList(scene, "nodes", "scene " + std::to_string(i++));
    i = 0;
    for (const nlohmann::json& node : array("nodes")) {
        const std::string what = "node " + std::to_string(i++);
        for (const char* key : {"mesh", "camera", "skin"})
            index(node, key, what);
        indexList(node, "children", what);
    }
    i = 0;
    for (const nlohmann::json& mesh : array("meshes")) {
        const std::string what = "mesh " + std::to_string(i++);
        if (!mesh.is_object() || !mesh.contains("primitives") || !mesh["primitives"].is_array())
            continue;
        size_t p = 0;
        for (const nlohmann::json& primitive : mesh["primitives"]) {
            const std::string where = what + " primitive " + std::to_string(p++);
            index(primitive, "indices", where);
            index(primitive, "material", where);
            integer(primitive, "mode", where, "primitive mode");
            if (primitive.is_object() && primitive.contains("attributes") &&
                primitive["attributes"].is_object())
                for (const auto& [name, accessor] : primitive["attributes"].items())
                    if (!(accessor.is_number_integer() || accessor.is_number_unsigned()) ||
                        accessor.get<double>() < 0 || accessor.get<double>() > 2147483647.0)
                        fail(path, where + ": attribute " + name + " " + accessor.dump() +
                                       " is not an accessor index (0 or more)");
        }
    }
    i = 0;
    for (const nlohmann::json& accessor : array("accessors")) {
        const std::string what = "accessor " + std::to_string(i++);
        index(accessor, "bufferView", what);
        if (accessor.is_object() && accessor.contains("sparse") && accessor["sparse"].is_object())
            for (const char* part : {"indices", "values"})
                if (accessor["sparse"].contains(part))
                    index(accessor["sparse"][part], "bufferView",
                          what + " sparse " + std::string(part));
    }
    i = 0;
    for (const nlohmann::json& view : array("bufferViews"))
        index(view, "buffer", "buffer view " + std::to_string(i++));
    i = 0;
    for (const nlohmann::json& image : array("images"))
        index(image, "bufferView", "image " + std::to_string(i++));

    // Every extension named anywhere (extensionsUsed, and the objects' "extensions").
    std::set<std::string> used;
    for (const nlohmann::json& name : array("extensionsUsed"))
        if (name.is_string()) used.insert(name.get<std::string>());
    std::vector<const nlohmann::json*> stack = {&root};
    for (size_t visited = 0; !stack.empty() && visited < 1000000; ++visited) {
        const nlohmann::json* node = stack.back();
        stack.pop_back();
        if (node->is_object()) {
            for (const auto& [key, value] : node->items()) {
                if (key == "extensions" && value.is_object())
                    for (const auto& [name, body] : value.items())
                        used.insert(name);
                if (value.is_structured()) stack.push_back(&value);
            }
        } else if (node->is_array()) {
            for (const nlohmann::json& value : *node)
                if (value.is_structured()) stack.push_back(&value);
        }
    }
    for (const std::string& name : used) {
        if (name == "KHR_lights_punctual" || name == "KHR_materials_emissive_strength") continue;
        if (name.rfind("KHR_materials_", 0) == 0) continue; // named with the materials
        if (name == "KHR_draco_mesh_compression")
            warnings.once("glTF extension KHR_draco_mesh_compression is ignored: compressed "
                          "primitives are read from their plain accessors (an accessor without "
                          "a buffer view is zeros)");
        else if (name == "KHR_texture_transform")
            warnings.once("glTF extension KHR_texture_transform is ignored: textures are drawn "
                          "without their offset, rotation and scale");
        else
            warnings.once("glTF extension " + name + " is ignored");
    }
}

} // namespace ssgi
