#include "scene/scene_json.h"

#include "scene/gltf_internal.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <set>
#include <sstream>

namespace ssgi {
namespace {

using Json = nlohmann::json;

// Allowed values of a number; anything outside is a typo or a unit mistake, not a scene.
struct Range {
    double lo, hi;
    bool openLo = false, openHi = false;
    bool contains(double x) const {
        return (openLo ? x > lo : x >= lo) && (openHi ? x < hi : x <= hi);
    }
    std::string text() const {
        std::ostringstream out;
        out << (openLo ? "(" : "[") << lo << ", " << hi << (openHi ? ")" : "]");
        return out.str();
    }
};
// Far beyond any real scene in any unit, yet well inside float range.
constexpr Range kCoordinate{-1e9, 1e9};
constexpr Range kLength{0.0, 1e9, true};
constexpr Range kColor{0.0, 1e6};
constexpr Range kAlbedo{0.0, kMaxAlbedo};
// Path times: the programs walk a path from time 0 (render --time, walkthrough), so a key before
// it would never be seen.
constexpr Range kTime{0.0, 1e9};
// Levels of arrays and objects a scene file may nest (it needs five).
constexpr size_t kMaxJsonDepth = 64;

std::string formatNumber(double x) {
    std::ostringstream out;
    out << x;
    return out.str();
}

// One JSON object of the file, with its path for messages ("light", "objects[2]").
class JsonObject {
public:
    JsonObject(const std::string& file, const Json& value, std::string path)
        : file_(file), value_(value), path_(std::move(path)) {}

    void allowOnly(std::initializer_list<const char*> keys) const {
        for (const auto& item : value_.items()) {
            if (std::find(keys.begin(), keys.end(), item.key()) != keys.end()) continue;
            throw InputError(file_ + ": unknown key '" + item.key() + "' " +
                             (path_.empty() ? "at top level" : "in '" + path_ + "'"));
        }
    }
    bool has(const char* key) const { return value_.contains(key); }
    std::string name(const std::string& key) const {
        return path_.empty() ? key : path_ + "." + key;
    }
    [[noreturn]] void fail(const std::string& key, const std::string& problem) const {
        throw InputError(file_ + ": '" + name(key) + "' " + problem);
    }

    double number(const char* key, Range range) const {
        return checkedNumber(value_.at(key), key, range);
    }
    std::optional<float> optionalNumber(const char* key, Range range) const {
        if (!has(key)) return std::nullopt;
        return float(number(key, range));
    }
    int integer(const char* key, Range range) const {
        const double x = number(key, range);
        if (x != std::floor(x)) fail(key, "must be a whole number");
        return int(x);
    }
    glm::vec3 vec3(const char* key, Range range) const {
        return checkedVec3(value_.at(key), key, range);
    }
    // An array of `count` points, each named "key[i]" in messages.
    std::vector<glm::vec3> points(const char* key, size_t count, Range range) const {
        const Json& array = value_.at(key);
        if (!array.is_array() || array.size() != count)
            fail(key, "must be an array of " + std::to_string(count) + " points");
        std::vector<glm::vec3> result;
        for (size_t i = 0; i < count; ++i)
            result.push_back(
                checkedVec3(array[i], std::string(key) + "[" + std::to_string(i) + "]", range));
        return result;
    }
    std::optional<glm::vec3> optionalVec3(const char* key, Range range) const {
        if (!has(key)) return std::nullopt;
        return vec3(key, range);
    }
    bool boolean(const char* key) const {
        if (!value_.at(key).is_boolean()) fail(key, "must be true or false");
        return value_.at(key).get<bool>();
    }
    std::string string(const char* key) const {
        if (!value_.at(key).is_string()) fail(key, "must be a string");
        return value_.at(key).get<std::string>();
    }
    JsonObject object(const std::string& key) const { return objectAt(value_.at(key), name(key)); }
    // The objects of an array-valued key, named "key[i]".
    std::vector<JsonObject> objects(const char* key) const {
        if (!value_.at(key).is_array()) fail(key, "must be an array");
        std::vector<JsonObject> result;
        for (size_t i = 0; i < value_.at(key).size(); ++i)
            result.push_back(
                objectAt(value_.at(key)[i], name(key) + "[" + std::to_string(i) + "]"));
        return result;
    }
    const Json& value() const { return value_; }
    const std::string& file() const { return file_; }
    const std::string& path() const { return path_; }

private:
    JsonObject objectAt(const Json& value, const std::string& path) const {
        if (!value.is_object()) throw InputError(file_ + ": '" + path + "' must be an object");
        return JsonObject(file_, value, path);
    }
    glm::vec3 checkedVec3(const Json& array, const std::string& key, Range range) const {
        if (!array.is_array() || array.size() != 3) fail(key, "must be an array of 3 numbers");
        glm::vec3 v;
        for (int i = 0; i < 3; ++i)
            v[i] = float(checkedNumber(array[size_t(i)], key, range));
        return v;
    }
    double checkedNumber(const Json& value, const std::string& key, Range range) const {
        if (!value.is_number()) fail(key, "must be a number");
        const double x = value.get<double>();
        if (!std::isfinite(x)) fail(key, "must be a finite number");
        if (!range.contains(x)) fail(key, "is " + formatNumber(x) + ", must be in " + range.text());
        return x;
    }

    const std::string& file_;
    const Json& value_;
    std::string path_;
};

CameraSpec readCameraKeys(const JsonObject& in) {
    CameraSpec camera;
    camera.where = in.path();
    camera.position = in.optionalVec3("position", kCoordinate);
    camera.target = in.optionalVec3("target", kCoordinate);
    camera.direction = in.optionalVec3("direction", kCoordinate);
    camera.up = in.optionalVec3("up", kCoordinate);
    camera.yfovDegrees = in.optionalNumber("yfov_deg", {kMinFovDegrees, 179.0, false, true});
    camera.znear = in.optionalNumber("near", kLength);
    camera.zfar = in.optionalNumber("far", kLength);
    if (camera.target && camera.direction) in.fail("target", "and 'direction' exclude each other");
    if (camera.direction && glm::length(*camera.direction) == 0.0f)
        in.fail("direction", "must not be zero");
    if (camera.up && glm::length(*camera.up) == 0.0f) in.fail("up", "must not be zero");
    if (camera.znear && camera.zfar && *camera.znear >= *camera.zfar)
        in.fail("near", "must be less than 'far'");
    return camera;
}

LightSpec readLight(const JsonObject& in) {
    in.allowOnly({"position", "direction", "target", "color", "intensity", "cone_deg",
                  "inner_cone_deg", "radius"});
    LightSpec light;
    light.position = in.optionalVec3("position", kCoordinate);
    light.direction = in.optionalVec3("direction", kCoordinate);
    light.target = in.optionalVec3("target", kCoordinate);
    light.color = in.optionalVec3("color", kColor);
    light.intensity = in.optionalNumber("intensity", {0.0, 1e12});
    light.coneDegrees = in.optionalNumber("cone_deg", {0.0, 89.0, true, true});
    light.innerConeDegrees = in.optionalNumber("inner_cone_deg", {0.0, 89.0, false, true});
    light.radius = in.optionalNumber("radius", {0.0, 1e9});
    if (light.target && light.direction) in.fail("target", "and 'direction' exclude each other");
    if (light.direction && glm::length(*light.direction) == 0.0f)
        in.fail("direction", "must not be zero");
    if (light.innerConeDegrees && *light.innerConeDegrees >= light.coneDegrees.value_or(89.0f))
        in.fail("inner_cone_deg", "must be less than 'cone_deg'");
    return light;
}

Sky readSky(const JsonObject& in) {
    in.allowOnly({"color", "zenith", "horizon", "ground"});
    Sky sky;
    if (in.has("color")) {
        if (in.has("zenith") || in.has("horizon") || in.has("ground"))
            in.fail("color", "excludes 'zenith', 'horizon' and 'ground'");
        sky.zenith = sky.horizon = sky.ground = in.vec3("color", kColor);
        return sky;
    }
    sky.zenith = in.optionalVec3("zenith", kColor).value_or(glm::vec3(0.0f));
    sky.horizon = in.optionalVec3("horizon", kColor).value_or(glm::vec3(0.0f));
    sky.ground = in.optionalVec3("ground", kColor).value_or(glm::vec3(0.0f));
    return sky;
}

ObjectSpec readObject(const JsonObject& in) {
    ObjectSpec object;
    object.where = in.path();
    if (!in.has("type")) in.fail("type", "is missing");
    if (!in.has("material")) in.fail("material", "is missing");
    const std::string type = in.string("type");
    object.material = in.string("material");
    if (in.has("name")) object.name = in.string("name");
    if (type == "quad") {
        in.allowOnly({"type", "name", "material", "corners"});
        if (!in.has("corners")) in.fail("corners", "is missing");
        const std::vector<glm::vec3> corners = in.points("corners", 4, kCoordinate);
        std::copy(corners.begin(), corners.end(), object.corners.begin());
    } else if (type == "box") {
        in.allowOnly({"type", "name", "material", "center", "size", "rotate_y_deg"});
        object.type = ObjectSpec::Type::Box;
        if (!in.has("center") || !in.has("size")) in.fail("center", "and 'size' are required");
        object.center = in.vec3("center", kCoordinate);
        object.size = in.vec3("size", kLength);
        object.rotateYDegrees = in.optionalNumber("rotate_y_deg", {-360.0, 360.0}).value_or(0.0f);
    } else if (type == "sphere") {
        in.allowOnly({"type", "name", "material", "center", "radius", "segments"});
        object.type = ObjectSpec::Type::Sphere;
        if (!in.has("center") || !in.has("radius")) in.fail("center", "and 'radius' are required");
        object.center = in.vec3("center", kCoordinate);
        object.radius = float(in.number("radius", kLength));
        if (in.has("segments")) object.segments = in.integer("segments", {3.0, 1024.0});
    } else {
        in.fail("type", "is '" + type + "', must be quad, box or sphere");
    }
    return object;
}

ObjectPath readObjectPath(const JsonObject& in) {
    in.allowOnly({"object", "keys"});
    if (!in.has("object")) in.fail("object", "is missing");
    if (!in.has("keys")) in.fail("keys", "is missing");
    ObjectPath path;
    path.object = in.string("object");
    for (const JsonObject& key : in.objects("keys")) {
        key.allowOnly({"time", "translation"});
        if (!key.has("time")) key.fail("time", "is missing");
        ObjectKey k;
        k.time = float(key.number("time", kTime));
        if (!path.keys.empty() && k.time <= path.keys.back().time)
            key.fail("time", "is not later than the key before it; keys must be sorted by time");
        k.translation = key.optionalVec3("translation", kCoordinate).value_or(glm::vec3(0.0f));
        path.keys.push_back(k);
    }
    if (path.keys.empty()) in.fail("keys", "is empty");
    return path;
}

SettingOverrides readSettings(const JsonObject& in) {
    SettingOverrides settings;
    for (const auto& item : in.value().items()) {
        const std::string& key = item.key();
        if (!item.value().is_number())
            throw InputError(in.file() + ": setting '" + key + "' must be a number");
        settings[key] = checkSetting(in.file(), key, item.value().get<double>());
    }
    return settings;
}

} // namespace

SceneDescription readSceneDescription(const std::string& path) {
    const std::string text = readInputFile(path);
    Json document;
    try {
        // JSON allows a key twice in one object, and the parser keeps the last: a scene file
        // that says "intensity" twice would silently lose the first. That is an error here.
        struct Open {
            std::string name; // "light", "objects[]": where it is, for the message
            bool isObject = false;
            std::set<std::string> keys;
        };
        std::vector<Open> open;
        std::string lastKey;
        auto nameOfNext = [&] {
            return open.empty()           ? std::string()
                   : open.back().isObject ? lastKey
                                          : open.back().name + "[]";
        };
        document = Json::parse(text, [&](int, Json::parse_event_t event, Json& parsed) {
            switch (event) {
            case Json::parse_event_t::object_start:
            case Json::parse_event_t::array_start:
                // Scene files nest a few levels; a deeper file is not a scene, and the levels'
                // names would grow with the square of its depth (each holds its parent's).
                if (open.size() >= kMaxJsonDepth)
                    throw InputError(path + ": JSON nested more than " +
                                     std::to_string(kMaxJsonDepth) + " levels deep");
                open.push_back({nameOfNext(), event == Json::parse_event_t::object_start, {}});
                break;
            case Json::parse_event_t::object_end:
            case Json::parse_event_t::array_end:
                if (!open.empty()) open.pop_back();
                break;
            case Json::parse_event_t::key:
                lastKey = parsed.get<std::string>();
                if (!open.empty() && !open.back().keys.insert(lastKey).second)
                    throw InputError(path + ": the key '" + lastKey + "' appears twice in " +
                                     (open.back().name.empty() ? std::string("the top-level object")
                                                               : "'" + open.back().name + "'") +
                                     " (JSON would silently keep only the last)");
                break;
            default:
                break;
            }
            return true;
        });
    } catch (const Json::parse_error& error) {
        // what() starts with "[json.exception.parse_error.101] ", which helps nobody.
        std::string detail = error.what();
        detail.erase(0, detail.find("] ") == std::string::npos ? 0 : detail.find("] ") + 2);
        throw InputError(path + ": malformed JSON at byte " + std::to_string(error.byte) + ": " +
                         detail);
    } catch (const Json::out_of_range& error) {
        // A number beyond double range ("1e999") is reported as out_of_range, not parse_error.
        std::string detail = error.what();
        detail.erase(0, detail.find("] ") == std::string::npos ? 0 : detail.find("] ") + 2);
        throw InputError(path + ": malformed JSON: " + detail);
    }
    if (!document.is_object()) throw InputError(path + ": a scene file must hold a JSON object");
    const JsonObject top(path, document, "");
    top.allowOnly({"description", "gltf", "gltf_scale", "materials", "objects", "light", "sky",
                   "camera", "camera_path", "object_paths", "settings"});
    SceneDescription scene;
    if (top.has("description")) top.string("description");
    if (top.has("gltf")) {
        const Json& gltf = document["gltf"];
        const bool listOfStrings =
            gltf.is_array() && std::all_of(gltf.begin(), gltf.end(),
                                           [](const Json& name) { return name.is_string(); });
        if (!gltf.is_string() && !listOfStrings)
            top.fail("gltf", "must be a string or an array of strings");
        // Paths in a scene file are relative to the file, so it works from any directory.
        const std::filesystem::path folder = std::filesystem::path(path).parent_path();
        for (const Json& name : gltf.is_string() ? Json::array({gltf}) : gltf)
            scene.gltfPaths.push_back((folder / name.get<std::string>()).string());
    }
    scene.gltfScale = top.optionalNumber("gltf_scale", {0.0, 1e9, true}).value_or(1.0f);
    if (top.has("materials")) {
        const JsonObject materials = top.object("materials");
        for (const auto& item : materials.value().items()) {
            const JsonObject in = materials.object(item.key());
            in.allowOnly({"albedo"});
            Material material;
            material.name = item.key();
            const glm::vec3 albedo = in.optionalVec3("albedo", kAlbedo).value_or(glm::vec3(0.8f));
            material.baseColorFactor = glm::vec4(albedo, 1.0f);
            scene.materials.push_back(material);
        }
    }
    if (top.has("objects")) {
        for (const JsonObject& in : top.objects("objects")) {
            ObjectSpec object = readObject(in);
            const bool known =
                std::any_of(scene.materials.begin(), scene.materials.end(),
                            [&](const Material& m) { return m.name == object.material; });
            if (!known) in.fail("material", "is '" + object.material + "', not in 'materials'");
            scene.objects.push_back(object);
        }
    }
    if (top.has("light")) scene.light = readLight(top.object("light"));
    if (top.has("sky")) scene.sky = readSky(top.object("sky"));
    if (top.has("camera")) {
        const JsonObject in = top.object("camera");
        in.allowOnly({"position", "target", "direction", "up", "yfov_deg", "near", "far"});
        scene.camera = readCameraKeys(in);
    }
    if (top.has("camera_path")) {
        for (const JsonObject& in : top.objects("camera_path")) {
            in.allowOnly({"time", "position", "target", "direction", "up", "yfov_deg", "near",
                          "far", "cut"});
            if (!in.has("time")) in.fail("time", "is missing");
            const float time = float(in.number("time", kTime));
            // Equal times are allowed: they make a camera cut.
            if (!scene.cameraPath.empty() && time < scene.cameraPath.back().first)
                in.fail("time", "is earlier than the key before it; keys must be sorted by time");
            CameraSpec key = readCameraKeys(in);
            key.cut = in.has("cut") && in.boolean("cut");
            scene.cameraPath.emplace_back(time, key);
        }
    }
    if (top.has("object_paths"))
        for (const JsonObject& in : top.objects("object_paths"))
            scene.objectPaths.push_back(readObjectPath(in));
    if (top.has("settings")) scene.settings = readSettings(top.object("settings"));
    return scene;
}

} // namespace ssgi
