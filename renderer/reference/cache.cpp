#include "reference/cache.h"

#include "reference/random.h"
#include "scene/animation.h"
#include "scene/sealed.h"
#include "scene/warnings.h"

#include "atomic_file.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <pwd.h>
#include <sys/stat.h>
#include <type_traits>
#include <unistd.h>

namespace ssgi::reference {
namespace {

namespace fs = std::filesystem;

// Bump whenever an estimator or a stopping rule changes what it computes: every cached image
// becomes stale.
constexpr uint64_t kVersion = 2;
constexpr char kMagic[8] = {'S', 'S', 'G', 'I', 'R', 'E', 'F', '3'};

// Two independent 64-bit lanes over the bytes; not cryptographic, which a cache of our own
// renders does not need, but 128 bits make an accidental collision out of the question.
class Hasher {
public:
    void bytes(const void* data, size_t size) {
        add(data, size);
        value(uint64_t(size)); // so that ("ab", "c") and ("a", "bc") differ
    }
    template <class T> void value(const T& v) {
        static_assert(std::is_trivially_copyable_v<T>);
        add(&v, sizeof(T));
    }
    template <class T> void vector(const std::vector<T>& v) {
        bytes(v.data(), v.size() * sizeof(T));
    }
    std::string hex() const {
        char text[33];
        std::snprintf(text, sizeof text, "%016llx%016llx", (unsigned long long)mix64(a_),
                      (unsigned long long)mix64(b_ ^ a_));
        return text;
    }

private:
    void add(const void* data, size_t size) {
        const auto* p = static_cast<const unsigned char*>(data);
        for (size_t i = 0; i < size; i += 8) {
            uint64_t word = 0;
            std::memcpy(&word, p + i, std::min<size_t>(8, size - i));
            a_ = mix64(a_ ^ word) + 0x9e3779b97f4a7c15ull;
            b_ = mix64(b_ + word * 0xff51afd7ed558ccdull) ^ (b_ >> 17);
        }
    }

    uint64_t a_ = 0x243f6a8885a308d3ull, b_ = 0x13198a2e03707344ull;
};

void hashScene(Hasher& h, const Scene& scene) {
    // Field by field, never whole structs: padding bytes are not content.
    for (const Mesh& mesh : scene.meshes) {
        h.vector(mesh.vertices); // Vertex is 40 bytes with no padding (static_assert in scene.h)
        h.vector(mesh.indices);
        h.value(mesh.material);
        h.value(uint8_t(mesh.vertexColors));
    }
    for (const Material& m : scene.materials) {
        h.value(m.baseColorFactor);
        h.value(m.baseColorTexture);
        const TextureSampler& sampler = m.baseColorSampler;
        for (uint8_t v : {uint8_t(sampler.wrapU), uint8_t(sampler.wrapV),
                          uint8_t(sampler.magnifyNearest), uint8_t(sampler.minifyNearest)})
            h.value(v);
        h.value(uint8_t(m.alphaMask));
        h.value(m.alphaCutoff);
    }
    for (const Texture& t : scene.textures) {
        h.value(t.width);
        h.value(t.height);
        h.vector(t.rgba);
    }
    for (const Instance& i : scene.instances) {
        h.value(i.mesh);
        h.value(i.transform);
    }
    const SpotLight& l = scene.light;
    for (const glm::vec3& v : {l.position, l.direction, l.color})
        h.value(v);
    for (float f : {l.intensity, l.innerConeAngle, l.outerConeAngle, l.radius})
        h.value(f);
    for (const glm::vec3& v : {scene.sky.zenith, scene.sky.horizon, scene.sky.ground})
        h.value(v);
    h.value(scene.bounds.min);
    h.value(scene.bounds.max);
    h.value(aoRadius(scene)); // the one setting the reference reads
}

// An entry: the header, the pixels, then the checksum of its key and both (32 hex digits), so
// that a damaged entry (bytes overwritten, cut short, values that cannot be) is never served,
// nor an entry copied under another request's key (its name): the key is not in the file, so
// the checksum only matches under the name it was written for.
constexpr size_t kHeaderBytes = 8 + 4 + 4 + 4 + 8 + 8, kChecksumBytes = 32;

template <class T> void put(std::string& out, const T& v) {
    out.append(reinterpret_cast<const char*>(&v), sizeof(T));
}
template <class T> T take(const std::string& in, size_t& at) {
    T v;
    std::memcpy(&v, in.data() + at, sizeof(T));
    at += sizeof(T);
    return v;
}

std::string checksum(const std::string& key, const char* data, size_t size) {
    Hasher h;
    h.bytes(key.data(), key.size());
    h.bytes(data, size);
    return h.hex();
}

std::string encodeEntry(const std::string& key, const ReferenceImage& image) {
    std::string out(kMagic, 8);
    put(out, image.width);
    put(out, image.height);
    put(out, image.samples);
    put(out, image.noise);
    put(out, image.nonFiniteSamples);
    out.append(reinterpret_cast<const char*>(image.rgba.data()), image.rgba.size() * 4);
    out += checksum(key, out.data(), out.size());
    return out;
}

// What is wrong with the entry at `file` (named by `key`), or "" when `image` holds it. A missing
// entry is "".
std::string readCached(const fs::path& file, const std::string& key,
                       const ReferenceOptions& options, ReferenceImage& image, bool& found) {
    found = false;
    struct stat status {};
    if (::lstat(file.c_str(), &status) != 0) return "";
    found = true;
    // Looked at before it is opened: a FIFO would block the read.
    if (!S_ISREG(status.st_mode)) return "not a regular file";
    const size_t pixels = size_t(options.width) * options.height;
    const size_t expected = kHeaderBytes + pixels * 16 + kChecksumBytes;
    if (size_t(status.st_size) != expected)
        return std::to_string(status.st_size) + " bytes where " + std::to_string(expected) +
               " were expected";
    std::ifstream in(file, std::ios::binary);
    std::string bytes(expected, '\0');
    if (!in.read(bytes.data(), std::streamsize(expected))) return "cannot be read";
    if (std::memcmp(bytes.data(), kMagic, 8) != 0)
        return "not a reference cache entry of this version";
    const size_t body = expected - kChecksumBytes;
    if (bytes.compare(body, kChecksumBytes, checksum(key, bytes.data(), body)) != 0)
        return "its checksum does not match its contents and its name";
    size_t at = 8;
    image.width = take<uint32_t>(bytes, at);
    image.height = take<uint32_t>(bytes, at);
    image.samples = take<uint32_t>(bytes, at);
    image.noise = take<double>(bytes, at);
    image.nonFiniteSamples = take<uint64_t>(bytes, at);
    if (image.width != options.width || image.height != options.height)
        return "its size is not the one asked for";
    if (image.samples < 1 || image.samples > options.spp)
        return std::to_string(image.samples) + " samples per pixel, outside 1.." +
               std::to_string(options.spp);
    if (!(std::isnan(image.noise) || (image.noise >= 0.0 && std::isfinite(image.noise))))
        return "its noise estimate is impossible";
    if (image.nonFiniteSamples > uint64_t(image.samples) * pixels)
        return "it counts more dropped samples than it took";
    image.rgba.resize(pixels * 4);
    std::memcpy(image.rgba.data(), bytes.data() + at, pixels * 16);
    if (!std::all_of(image.rgba.begin(), image.rgba.end(),
                     [](float v) { return std::isfinite(v); }))
        return "it holds values that are NaN or infinite";
    return "";
}

} // namespace

std::string defaultCacheDir() {
    if (const char* env = std::getenv("SSGI_REFERENCE_CACHE"); env && *env) return env;
    // The build tree's cache while the build tree is there; an installed program, whose build
    // tree may be gone, uses the user's cache folder.
    const fs::path build = fs::path(SSGI_REFERENCE_CACHE_DIR).parent_path();
    std::error_code ec;
    if (fs::is_directory(build, ec)) return SSGI_REFERENCE_CACHE_DIR;
    if (const char* xdg = std::getenv("XDG_CACHE_HOME"); xdg && *xdg)
        return (fs::path(xdg) / "ssgi" / "reference").string();
    const char* home = std::getenv("HOME");
    if (!home || !*home)
        if (const passwd* user = ::getpwuid(::getuid())) home = user->pw_dir;
    if (home && *home && fs::is_directory(home, ec))
        return (fs::path(home) / ".cache" / "ssgi" / "reference").string();
    // No home: a folder of this user's own in the temporary folder, never one that every user
    // of the machine shares (anyone could put a wrong ground truth there).
    const fs::path own =
        fs::temp_directory_path(ec) / ("ssgi-reference-cache-" + std::to_string(::getuid()));
    ::mkdir(own.c_str(), 0700);
    struct stat status {};
    if (::lstat(own.c_str(), &status) != 0 || !S_ISDIR(status.st_mode) ||
        status.st_uid != ::getuid() || (status.st_mode & 077) != 0) {
        warn("reference cache " + own.string() +
             " is not a private folder of this user; nothing is cached (set "
             "SSGI_REFERENCE_CACHE or HOME)");
        return "";
    }
    return own.string();
}

std::string referenceKey(const Scene& scene, const Camera& camera,
                         const ReferenceOptions& options) {
    Hasher h;
    h.value(kVersion);
    hashScene(h, scene);
    h.value(camera.position);
    h.value(camera.orientation);
    for (float f : {camera.yfov, camera.znear, camera.zfar})
        h.value(f);
    h.value(int(options.mode));
    for (uint32_t v : {options.width, options.height, options.spp})
        h.value(v);
    h.value(options.noiseTarget);
    h.value(options.seed);
    h.value(uint8_t(options.jitter));
    return h.hex();
}

ReferenceImage cachedReference(const Scene& scene, const Camera& camera,
                               const ReferenceOptions& options, const std::string& cacheDir,
                               bool* fromCache) {
    if (fromCache) *fromCache = false;
    if (cacheDir.empty()) return renderReference(scene, camera, options);
    const std::string key = referenceKey(scene, camera, options);
    const fs::path file = fs::path(cacheDir) / (key + ".ref");
    ReferenceImage image;
    bool found = false;
    const std::string damage = readCached(file, key, options, image, found);
    if (found && damage.empty()) {
        if (fromCache) *fromCache = true;
        return image;
    }
    if (found)
        warn("reference cache entry " + file.string() + " is damaged (" + damage +
             "); rendering it again");
    image = renderReference(scene, camera, options);
    try {
        std::error_code ec;
        fs::create_directories(cacheDir, ec);
        writeFilesAtomically({{file.string(), encodeEntry(key, image), true}});
    } catch (const std::exception& error) {
        warn("reference cache " + cacheDir + ": the image is not stored: " + error.what());
    }
    return image;
}

ReferenceImage cachedReference(const Scene& scene, const ReferenceOptions& options) {
    return cachedReference(scene, scene.camera, options);
}

ReferenceImage requestedReference(Scene scene, const std::string& sceneName,
                                  const ReferenceRequest& request, bool* fromCache) {
    const Mode mode = request.options.mode;
    if (request.options.jitter && mode != Mode::Full && mode != Mode::Multi)
        throw InputError("--jitter: only for --mode full or multi; the per-effect modes sample "
                         "pixel centres so that their edges match the real-time image");
    if (request.lightRadius >= 0.0f) scene.light.radius = request.lightRadius;
    Camera camera = scene.camera;
    if (request.time >= 0.0f) {
        camera = cameraAtTime(scene, request.time, sceneName);
        scene = posedAt(scene, request.time);
    } else {
        scene = posedAt(scene, std::numeric_limits<float>::lowest()); // the paths' first keys
    }
    // The image is right (black but for the sky), but most likely not what was meant.
    std::vector<glm::mat4> transforms;
    for (const Instance& instance : scene.instances)
        transforms.push_back(instance.transform);
    const float aspect = float(request.options.width) / float(request.options.height);
    if (const auto seal = LightSeals(scene).find(scene.light, camera, aspect, transforms))
        warn(sealWarning(*seal));
    if (fromCache) *fromCache = false;
    return request.useCache
               ? cachedReference(scene, camera, request.options, request.cacheDir, fromCache)
               : renderReference(scene, camera, request.options);
}

} // namespace ssgi::reference
