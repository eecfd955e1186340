#include "viewer/camera_path_io.h"

#include "app/cli.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace ssgi::viewer {

using Json = nlohmann::ordered_json; // keeps the file's own key order

void PathRecorder::start() {
    path_.keys.clear();
    time_ = sinceKey_ = 0.0f;
    recording_ = true;
}

void PathRecorder::update(const Camera& camera, float seconds) {
    if (!recording_) return;
    if (!path_.keys.empty()) {
        time_ += seconds;
        sinceKey_ += seconds;
        if (sinceKey_ < interval) return;
    }
    sinceKey_ = 0.0f;
    path_.keys.push_back({time_, camera});
}

float pathDuration(const CameraPath& path) {
    return path.empty() ? 0.0f : path.keys.back().time - path.keys.front().time;
}

namespace {

double rounded(double v) {
    return std::round(v * 1e5) / 1e5;
}

Json vec3(glm::vec3 v) {
    return Json::array({rounded(v.x), rounded(v.y), rounded(v.z)});
}

Json keyJson(const CameraKey& key) {
    const Camera& c = key.camera;
    Json j;
    j["time"] = rounded(key.time);
    j["position"] = vec3(c.position);
    j["direction"] = vec3(c.orientation * glm::vec3(0.0f, 0.0f, -1.0f));
    // A camera without roll (its right vector level) is written with the world's up, as a person
    // would write it; the loader derives the same orientation from it.
    const glm::vec3 right = c.orientation * glm::vec3(1.0f, 0.0f, 0.0f);
    const glm::vec3 up = c.orientation * glm::vec3(0.0f, 1.0f, 0.0f);
    j["up"] = vec3(std::abs(right.y) < 1e-4f && up.y > 0.0f ? glm::vec3(0.0f, 1.0f, 0.0f) : up);
    j["yfov_deg"] = rounded(glm::degrees(double(c.yfov)));
    return j;
}

bool scalar(const Json& j) {
    return !j.is_object() && !j.is_array();
}

// Scene files are written by hand: arrays of numbers and small objects stay on one line.
void print(std::ostringstream& out, const Json& j, int indent) {
    const std::string inner(size_t(indent + 2), ' ');
    const std::string compact = j.dump();
    const bool flat = std::all_of(j.begin(), j.end(), [](const Json& e) {
        return scalar(e) || (e.is_array() && std::all_of(e.begin(), e.end(), scalar));
    });
    if (scalar(j) || (flat && compact.size() + size_t(indent) <= 110)) {
        // One line, with a space after each separator as in the files in scenes/.
        std::string line = j.dump(-1, ' ', false);
        std::string spaced;
        bool inString = false;
        for (size_t i = 0; i < line.size(); ++i) {
            const char ch = line[i];
            if (ch == '"' && (i == 0 || line[i - 1] != '\\')) inString = !inString;
            spaced += ch;
            if (!inString && (ch == ',' || ch == ':')) spaced += ' ';
        }
        if (j.is_object() && !j.empty()) spaced = "{ " + spaced.substr(1, spaced.size() - 2) + " }";
        out << spaced;
        return;
    }
    const bool object = j.is_object();
    out << (object ? "{\n" : "[\n");
    size_t n = 0;
    for (auto it = j.begin(); it != j.end(); ++it, ++n) {
        out << inner;
        if (object) out << Json(it.key()).dump() << ": ";
        print(out, *it, indent + 2);
        out << (n + 1 < j.size() ? ",\n" : "\n");
    }
    out << std::string(size_t(indent), ' ') << (object ? "}" : "]");
}

} // namespace

void writeCameraPath(const std::string& source, const std::string& target, const CameraPath& path) {
    for (const std::string& file : {source, target})
        if (std::filesystem::path(file).extension() != ".json")
            throw InputError(file + ": camera paths can only be saved into .json scene files");
    std::ifstream in(source);
    if (!in) throw InputError(source + ": cannot read the scene file");
    Json scene;
    try {
        scene = Json::parse(in);
    } catch (const std::exception& e) {
        throw InputError(source + ": cannot parse the scene file: " + e.what());
    }
    Json keys = Json::array();
    for (const CameraKey& key : path.keys)
        keys.push_back(keyJson(key));
    scene["camera_path"] = keys;
    std::ostringstream text;
    print(text, scene, 0);
    text << "\n";
    // The scene file's relative paths (glTF) stay right only beside the original.
    cli::writeTextAtomically(target, text.str());
}

} // namespace ssgi::viewer
