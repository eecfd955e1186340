// Reading a glTF from disk: the file itself, and the buffers and images it names, opened only
// where they lie beside it (gltf_internal.h readGltfModel); its JSON checked around tinygltf's
// reading by gltf_json_checks.cpp.
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
