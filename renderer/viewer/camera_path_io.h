// Camera paths in the viewer: recording the camera as it moves, and writing a path back into a
// scene file's "camera_path" (the format the loader reads, so `render --time` and `walkthrough`
// replay it).
#pragma once

#include "scene/scene.h"

#include <string>

namespace ssgi::viewer {

// Records a key every `interval` seconds of viewer time while running.
class PathRecorder {
public:
    void start();
    void stop() { recording_ = false; }
    bool recording() const { return recording_; }
    void update(const Camera& camera, float seconds);
    const CameraPath& path() const { return path_; }
    float interval = 0.25f;

private:
    bool recording_ = false;
    float time_ = 0.0f, sinceKey_ = 0.0f;
    CameraPath path_;
};

// The path's length in seconds (0 for an empty path).
float pathDuration(const CameraPath& path);

// Writes `target` as a copy of the scene file `source` whose "camera_path" is `path` (source ==
// target rewrites it in place, atomically). Only .json scene files hold paths; InputError
// otherwise, or when the source cannot be read.
void writeCameraPath(const std::string& source, const std::string& target, const CameraPath& path);

} // namespace ssgi::viewer
