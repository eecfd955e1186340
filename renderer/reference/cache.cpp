#include "reference/cache.h"

#include "reference/random.h"
#include "scene/animation.h"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <type_traits>
#include <unistd.h>

namespace ssgi::reference {
namespace {

namespace fs = std::filesystem;

// Bump whenever an estimator changes what it computes: every cached image becomes stale.
constexpr uint64_t kVersion = 1;
constexpr char kMagic[8] = {'S', 'S', 'G', 'I', 'R', 'E', 'F', '1'};

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
        h.vector(mesh.vertices); // Vertex is 32 bytes with no padding (static_assert in scene.h)
        h.vector(mesh.indices);
        h.value(mesh.material);
    }
    for (const Material& m : scene.materials) {
        h.value(m.baseColorFactor);
        h.value(m.baseColorTexture);
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

bool readCached(const fs::path& file, ReferenceImage& image) {
    std::ifstream in(file, std::ios::binary);
    if (!in) return false;
    char magic[8];
    in.read(magic, 8);
    if (!in || std::memcmp(magic, kMagic, 8) != 0) return false;
    in.read(reinterpret_cast<char*>(&image.width), 4);
    in.read(reinterpret_cast<char*>(&image.height), 4);
    in.read(reinterpret_cast<char*>(&image.samples), 4);
    in.read(reinterpret_cast<char*>(&image.noise), 8);
    in.read(reinterpret_cast<char*>(&image.nonFiniteSamples), 8);
    if (!in || image.width == 0 || image.height == 0 || image.width > 65536 || image.height > 65536)
        return false;
    image.rgba.resize(size_t(image.width) * image.height * 4);
    in.read(reinterpret_cast<char*>(image.rgba.data()), std::streamsize(image.rgba.size() * 4));
    return bool(in) && in.peek() == EOF;
}

void writeCached(const fs::path& file, const ReferenceImage& image) {
    fs::create_directories(file.parent_path());
    const fs::path tmp =
        file.parent_path() / (".tmp-" + std::to_string(getpid()) + "-" + file.filename().string());
    {
        std::ofstream out(tmp, std::ios::binary);
        out.write(kMagic, 8);
        out.write(reinterpret_cast<const char*>(&image.width), 4);
        out.write(reinterpret_cast<const char*>(&image.height), 4);
        out.write(reinterpret_cast<const char*>(&image.samples), 4);
        out.write(reinterpret_cast<const char*>(&image.noise), 8);
        out.write(reinterpret_cast<const char*>(&image.nonFiniteSamples), 8);
        out.write(reinterpret_cast<const char*>(image.rgba.data()),
                  std::streamsize(image.rgba.size() * 4));
        if (!out) {
            std::error_code ec;
            fs::remove(tmp, ec);
            throw std::runtime_error(tmp.string() + ": cannot write");
        }
    }
    fs::rename(tmp, file); // atomic: a reader sees the old state or the whole file
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
    if (const char* home = std::getenv("HOME"); home && *home)
        return (fs::path(home) / ".cache" / "ssgi" / "reference").string();
    return (fs::temp_directory_path() / "ssgi-reference-cache").string();
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
    const fs::path file = fs::path(cacheDir) / (referenceKey(scene, camera, options) + ".ref");
    ReferenceImage image;
    if (readCached(file, image) && image.width == options.width && image.height == options.height) {
        if (fromCache) *fromCache = true;
        return image;
    }
    if (fromCache) *fromCache = false;
    image = renderReference(scene, camera, options);
    try {
        writeCached(file, image);
    } catch (const std::exception& error) {
        std::fprintf(stderr, "warning: reference cache %s: %s\n", cacheDir.c_str(), error.what());
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
    if (fromCache) *fromCache = false;
    return request.useCache
               ? cachedReference(scene, camera, request.options, request.cacheDir, fromCache)
               : renderReference(scene, camera, request.options);
}

} // namespace ssgi::reference
