// Reading a glTF from disk: the file itself, and the buffers and images it names, opened only
// where they lie beside it (gltf_internal.h readGltfModel).
#include "scene/gltf_internal.h"

#include "png_header.h"

#include <tiny_gltf.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <fcntl.h>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <mutex>
#include <sstream>
#include <sys/stat.h>
#include <unistd.h>

namespace ssgi {

namespace {

std::mutex gFilesReadMutex;
std::vector<std::string> gFilesRead; // each once (a fuzzer reads one path millions of times)
std::set<std::string> gFilesReadSet;

void noteRead(const std::string& path) {
    std::lock_guard lock(gFilesReadMutex);
    if (gFilesReadSet.insert(path).second) gFilesRead.push_back(path);
}

} // namespace

std::vector<std::string> filesRead() {
    std::lock_guard lock(gFilesReadMutex);
    return gFilesRead;
}

std::string readInputFile(const std::string& path) {
    // The system would read the path only up to the NUL: another file than the one named.
    if (const size_t nul = path.find('\0'); nul != std::string::npos)
        throw InputError(path.substr(0, nul) + "\\0" + path.substr(nul + 1) +
                         ": a path with a NUL character in it names no file");
    // The system's reason: a loop of symbolic links or a folder that may not be searched is not
    // a missing file.
    struct stat status {};
    if (::stat(path.c_str(), &status) != 0) {
        const int error = errno;
        if (error == ENOENT) throw InputError(path + ": file not found");
        if (error == ELOOP)
            throw InputError(path + ": a loop of symbolic links (or more than 40 of them) leads "
                                    "nowhere");
        throw InputError(path + ": cannot read: " + std::strerror(error));
    }
    if (!S_ISREG(status.st_mode)) throw InputError(path + ": not a regular file");
    std::ifstream in(path, std::ios::binary);
    if (!in) throw InputError(path + ": cannot open file for reading");
    std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (in.bad()) throw InputError(path + ": read error");
    noteRead(path);
    return bytes;
}

namespace {

[[noreturn]] void fail(const std::string& file, const std::string& problem) {
    throw InputError(file + ": " + problem);
}

std::string withoutTrailingSpace(std::string text) {
    while (!text.empty() && std::isspace(static_cast<unsigned char>(text.back())))
        text.pop_back();
    return text;
}

// The image decoder's own message for an image it will not decode is "Unknown image format",
// which is wrong for a valid PNG too large for it: such a PNG is named with its size.
bool loadImageSayingWhy(tinygltf::Image* image, const int index, std::string* error,
                        std::string* warning, int width, int height, const unsigned char* bytes,
                        int size, void* user) {
    // A PNG that cannot hold the pixels it declares, before the decoder allocates them.
    if (const std::string problem =
            pngSizeProblem(bytes, size_t(std::max(size, 0)), uint64_t(std::max(size, 0)));
        !problem.empty()) {
        if (error) *error = "image " + std::to_string(index) + " is a " + problem;
        return false;
    }
    if (tinygltf::LoadImageData(image, index, error, warning, width, height, bytes, size, user))
        return true;
    constexpr unsigned char kPng[] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
    if (size >= 24 && std::memcmp(bytes, kPng, 8) == 0 && std::memcmp(bytes + 12, "IHDR", 4) == 0 &&
        error) {
        auto bigEndian = [&](int at) {
            return uint32_t(bytes[at]) << 24 | uint32_t(bytes[at + 1]) << 16 |
                   uint32_t(bytes[at + 2]) << 8 | uint32_t(bytes[at + 3]);
        };
        *error = "image " + std::to_string(index) + " is a PNG of " +
                 std::to_string(bigEndian(16)) + "x" + std::to_string(bigEndian(20)) +
                 " pixels, which the image decoder refuses (it decodes up to 2^24 pixels a side "
                 "and 2 GB)";
    }
    return false;
}

// The files a glTF's buffers and images name. A URI is a path relative to the glTF's own folder
// (`..` allowed, as asset libraries share texture folders); never the working directory, which
// tinygltf tries next; never an absolute path or another scheme (`file:`, `http:`), which would
// make the file depend on the machine. Only regular files are opened, and without blocking: a
// FIFO or a device (`/dev/zero`, `/dev/stdin`) would hang the loader or fill the memory.
struct ExternalFiles {
    std::string folder;  // absolute, ends in '/'
    std::string problem; // the first refused URI, said instead of tinygltf's "File not found"

    static constexpr off_t kLargest = off_t(1) << 31; // stb_image's own limit is about 2 GB

    // The URI tinygltf joined to the folder, or "" for a candidate outside it (the CWD's).
    std::string uriOf(const std::string& joined) const {
        return joined.rfind(folder, 0) == 0 ? joined.substr(folder.size()) : std::string();
    }
    void refuse(const std::string& uri, const std::string& why) {
        if (problem.empty()) problem = "external file '" + uri + "' " + why;
    }
    static const char* kindOf(mode_t mode) {
        return S_ISDIR(mode)    ? "a folder"
               : S_ISFIFO(mode) ? "a FIFO"
               : S_ISCHR(mode)  ? "a character device"
               : S_ISBLK(mode)  ? "a block device"
               : S_ISSOCK(mode) ? "a socket"
                                : "not a regular file";
    }

    static bool exists(const std::string& joined, void* self) {
        auto& files = *static_cast<ExternalFiles*>(self);
        const std::string uri = files.uriOf(joined);
        if (uri.empty()) return false;
        if (uri.find('\0') != std::string::npos) {
            files.refuse(uri.substr(0, uri.find('\0')) + "\\0...",
                         "holds a NUL character; it names no file");
            return false;
        }
        if (uri[0] == '/' || uri[0] == '\\') {
            files.refuse(uri, "is an absolute path; glTF URIs are relative to the glTF's folder");
            return false;
        }
        // A data: URI tinygltf did not take as one (it takes base64 with the media types glTF
        // names) reaches here as if it were a file's name.
        if (uri.rfind("data:", 0) == 0) {
            const size_t end = uri.find_first_of(";,", 5);
            const std::string type = uri.substr(5, end == std::string::npos ? 0 : end - 5);
            const std::string shown = uri.size() > 40 ? uri.substr(0, 40) + "..." : uri;
            if (files.problem.empty())
                files.problem =
                    "data: URI '" + shown + "' " +
                    (type.empty() ? std::string("has no media type")
                     : type == "application/octet-stream" || type == "application/gltf-buffer" ||
                             type == "image/png" || type == "image/jpeg"
                         ? std::string("is not base64 (its media type is followed by ;base64,)")
                         : "has the media type '" + type + "', which glTF does not embed") +
                    ": an embedded buffer is data:application/octet-stream;base64,... or "
                    "data:application/gltf-buffer;base64,..., an embedded image "
                    "data:image/png;base64,... or data:image/jpeg;base64,...";
            return false;
        }
        const size_t colon = uri.find(':'), slash = uri.find('/');
        if (colon != std::string::npos && colon > 1 &&
            (slash == std::string::npos || colon < slash)) {
            files.refuse(uri, "is not a relative path (only files beside the glTF are read)");
            return false;
        }
        struct stat status {};
        if (::stat(joined.c_str(), &status) != 0) return false; // "File not found", naming it
        if (!S_ISREG(status.st_mode)) {
            files.refuse(uri, std::string("is ") + kindOf(status.st_mode) + ", not a regular file");
            return false;
        }
        return true;
    }
    static std::string expand(const std::string& path, void*) { return path; } // no `~`, no `$`
    static bool read(std::vector<unsigned char>* out, std::string* err, const std::string& joined,
                     void* self) {
        auto& files = *static_cast<ExternalFiles*>(self);
        const std::string uri = files.uriOf(joined);
        // O_NONBLOCK: a FIFO put in place after the stat above still does not hang the open.
        const int fd = ::open(joined.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
        if (fd < 0) {
            *err = std::strerror(errno);
            return false;
        }
        struct stat status {};
        bool ok = ::fstat(fd, &status) == 0;
        if (ok && !S_ISREG(status.st_mode)) {
            files.refuse(uri, std::string("is ") + kindOf(status.st_mode) + ", not a regular file");
            ok = false;
        } else if (ok && status.st_size > kLargest) {
            files.refuse(uri, "is larger than 2 GiB");
            ok = false;
        }
        if (ok) {
            out->resize(size_t(status.st_size));
            size_t done = 0;
            while (ok && done < out->size()) {
                const ssize_t n = ::read(fd, out->data() + done, out->size() - done);
                if (n < 0 && errno == EINTR) continue;
                if (n <= 0) {
                    *err = n < 0 ? std::strerror(errno) : "the file shrank while it was read";
                    ok = false;
                } else {
                    done += size_t(n);
                }
            }
        }
        ::close(fd);
        if (ok) noteRead(joined);
        return ok;
    }
    static bool write(std::string* err, const std::string&, const std::vector<unsigned char>&,
                      void*) {
        *err = "the loader writes no files";
        return false;
    }
};

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

} // namespace

tinygltf::Model readGltfModel(const std::string& path) {
    const std::string bytes = readInputFile(path);
    namespace fs = std::filesystem;
    ExternalFiles files;
    files.folder = fs::absolute(fs::path(path)).lexically_normal().parent_path().string();
    if (files.folder.empty() || files.folder.back() != '/') files.folder += '/';
    // tinygltf joins its base folder and the URI with one '/'; without the trailing one here.
    const std::string baseDir =
        files.folder.size() > 1 ? files.folder.substr(0, files.folder.size() - 1) : files.folder;
    tinygltf::TinyGLTF reader;
    reader.SetImageLoader(&loadImageSayingWhy, nullptr);
    reader.SetFsCallbacks({&ExternalFiles::exists, &ExternalFiles::expand, &ExternalFiles::read,
                           &ExternalFiles::write, &files});
    tinygltf::Model model;
    std::string error, warning;
    // Sniff the content rather than trust the extension: a .gltf holding GLB bytes still loads.
    const bool binary = bytes.size() >= 4 && std::memcmp(bytes.data(), "glTF", 4) == 0;
    const nlohmann::json root = gltfJson(bytes, binary);
    checkGltfJsonFirst(path, root);
    const bool ok =
        binary ? reader.LoadBinaryFromMemory(&model, &error, &warning,
                                             reinterpret_cast<const unsigned char*>(bytes.data()),
                                             static_cast<unsigned>(bytes.size()), baseDir)
               : reader.LoadASCIIFromString(&model, &error, &warning, bytes.data(),
                                            static_cast<unsigned>(bytes.size()), baseDir);
    error = withoutTrailingSpace(error);
    warning = withoutTrailingSpace(warning);
    if (!files.problem.empty()) fail(path, files.problem);
    if (!ok) {
        std::string message = "not a valid glTF file" + (error.empty() ? "" : ": " + error);
        if (!warning.empty()) message += " (" + warning + ")";
        fail(path, message);
    }
    GltfWarnings warnings(path);
    if (!warning.empty()) warnings.once(warning);
    for (const std::string& extension : model.extensionsRequired)
        if (extension != "KHR_lights_punctual" && extension != "KHR_materials_emissive_strength")
            fail(path, "requires the unsupported extension " + extension);
    checkGltfJson(path, root, warnings);
    return model;
}

} // namespace ssgi
