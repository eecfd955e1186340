// Reference images cached by content: the key hashes everything the image depends on (the
// loaded scene's geometry, materials, textures, light, sky and settings, the camera, the mode,
// size, sample count, noise target, seed, jitter and the estimators' version), so a second
// request for the same image is a file read, and any change to any input is a new key.
#pragma once

#include "reference/render.h"

#include <string>

namespace ssgi::reference {

// $SSGI_REFERENCE_CACHE, else build/reference-cache of the build tree, else the user's cache
// folder ($XDG_CACHE_HOME, $HOME/.cache or the home of the password database), else a private
// folder of the user's in the temporary folder; "" (nothing cached, with a warning) when that
// folder is not the user's own.
std::string defaultCacheDir();

// 32 hex digits naming the image that these inputs produce.
std::string referenceKey(const Scene& scene, const Camera& camera, const ReferenceOptions& options);

// The image from `cacheDir` when it is there, else rendered and stored there (written whole
// or not at all). Every entry carries a checksum and is checked against the request before it
// is believed: a damaged one (bytes changed, cut short, impossible values, not a regular file)
// is reported on stderr and rendered again. `fromCache`, when given, says which it was. A cache
// that cannot be written is reported on stderr and the rendered image returned all the same;
// an empty `cacheDir` caches nothing.
ReferenceImage cachedReference(const Scene& scene, const Camera& camera,
                               const ReferenceOptions& options,
                               const std::string& cacheDir = defaultCacheDir(),
                               bool* fromCache = nullptr);
// The scene's own camera.
ReferenceImage cachedReference(const Scene& scene, const ReferenceOptions& options);

// What the reference program renders of a loaded scene (and the Python module's reference()).
struct ReferenceRequest {
    ReferenceOptions options;
    // Seconds along the scene's camera path and object paths; < 0: none, the camera the scene's
    // own and the objects at their paths' first keys.
    float time = -1.0f;
    float lightRadius = -1.0f; // >= 0: replaces the light's disk radius
    bool useCache = true;
    std::string cacheDir = defaultCacheDir();
};

// The image `request` asks for, from the cache or rendered. `sceneName` names the scene in the
// InputError for a time given to a scene without paths; InputError for jitter in a mode other
// than full and multi.
ReferenceImage requestedReference(Scene scene, const std::string& sceneName,
                                  const ReferenceRequest& request, bool* fromCache = nullptr);

} // namespace ssgi::reference
