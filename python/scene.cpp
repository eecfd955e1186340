// ssgi.Scene: a scene file or a dict of the scene file's schema, loaded as the programs load it;
// picklable (it pickles as what it was loaded from, and the settings Python gave).
#include "module.h"

#include "scene/settings.h"

#include <pybind11/stl.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <unistd.h>

namespace ssgi::python {

SettingOverrides checkedOverrides(const py::handle& mapping); // settings.cpp
void defineSettings(py::module_& m);

namespace {

constexpr const char* kDictName = "<dict>"; // a scene made from a dict, in messages

std::string replaced(std::string text, const std::string& what, const std::string& with) {
    for (size_t at = text.find(what); at != std::string::npos; at = text.find(what, at))
        text.replace(at, what.size(), with), at += with.size();
    return text;
}

// A dict's scene through the loader, which reads files: its JSON in a file of a folder of its
// own, removed after. Messages name it "<dict>", not the file.
Scene loadJson(const std::string& json, const SettingOverrides& overrides) {
    std::string folder = (std::filesystem::temp_directory_path() / "ssgi-scene-XXXXXX").string();
    if (!::mkdtemp(folder.data()))
        throw InputError("scene: cannot make a temporary folder for a dict's scene");
    const std::string file = folder + "/scene.json";
    try {
        {
            std::ofstream out(file, std::ios::binary);
            out << json;
            if (!out) throw InputError("scene: cannot write a dict's scene to " + file);
        }
        Scene scene = loadScene(file, overrides);
        scene.sourcePath = kDictName;
        std::filesystem::remove_all(folder);
        return scene;
    } catch (const InputError& e) {
        std::filesystem::remove_all(folder);
        throw InputError(replaced(e.what(), file, kDictName));
    }
}

// A dict of the scene file's schema as JSON: its glTF paths, relative to `base` (a file's are
// relative to the file), made absolute. TypeError for what JSON cannot hold.
std::string jsonOf(const py::handle& scene, const std::string& base) {
    if (!py::isinstance<py::dict>(scene))
        throw ArgumentTypeError("scene: expected a dict of the scene file's schema, got " +
                                typeName(scene));
    const py::module_ json = py::module_::import("json");
    py::object copy;
    try {
        copy = json.attr("loads")(json.attr("dumps")(scene, py::arg("allow_nan") = false));
    } catch (py::error_already_set& e) {
        if (!e.matches(PyExc_TypeError) && !e.matches(PyExc_ValueError)) throw;
        throw ArgumentTypeError("scene: the dict is not one JSON holds: " +
                                std::string(py::str(e.value())));
    }
    py::dict d = copy;
    if (d.contains("gltf")) {
        const py::object os = py::module_::import("os.path");
        auto absolute = [&](const py::handle& name) -> py::object {
            if (!py::isinstance<py::str>(name)) return py::reinterpret_borrow<py::object>(name);
            return os.attr("join")(base, name); // an absolute name stays as it is
        };
        if (py::isinstance<py::list>(d["gltf"])) {
            py::list names;
            for (const py::handle name : d["gltf"])
                names.append(absolute(name));
            d["gltf"] = names;
        } else {
            d["gltf"] = absolute(d["gltf"]);
        }
    }
    return json.attr("dumps")(d).cast<std::string>();
}

std::shared_ptr<SceneObject> made(std::string path, std::string json,
                                  const SettingOverrides& overrides) {
    auto s = std::make_shared<SceneObject>();
    s->path = std::move(path);
    s->json = std::move(json);
    s->overrides = overrides;
    s->scene = std::make_shared<Scene>(loadSceneObject(*s, s->overrides));
    raiseWarnings();
    return s;
}

} // namespace

Scene loadSceneObject(const SceneObject& s, const SettingOverrides& overrides) {
    py::gil_scoped_release release;
    return s.json.empty() ? loadScene(s.path, overrides) : loadJson(s.json, overrides);
}

Scene& SceneObject::writable() {
    if (scene.use_count() > 1) scene = std::make_shared<Scene>(*scene);
    return *scene;
}

SceneObject& sceneArg(const std::shared_ptr<SceneObject>& scene) {
    if (!scene) throw ArgumentTypeError("scene: expected an ssgi.Scene, got None");
    return *scene;
}

void defineScene(py::module_& m) {
    defineSettings(m);
    py::class_<SceneObject, std::shared_ptr<SceneObject>>(
        m, "Scene",
        "A scene file (.json) or a bare glTF (.gltf, .glb), loaded as the programs load it, or a "
        "dict of the scene file's schema (from_dict). `settings` (a mapping) overrides method "
        "settings as --set does. The shipped scenes: ssgi.scene_names(), ssgi.scene_file(). A "
        "scene pickles (and copies) as what it was loaded from and the settings Python set.")
        .def(py::init([](const PathArg& path, const std::optional<SettingsArg>& settings) {
                 return made(pathFrom(path.value, "path"), "",
                             settings ? checkedOverrides(settings->value) : SettingOverrides{});
             }),
             py::arg("path"), py::arg("settings") = py::none(),
             "Loads the scene at `path` (str or os.PathLike) with `settings` overriding the "
             "method settings, as render --set does; ssgi.InputError with render's message for "
             "a file it refuses (ssgi.MissingFileError, a FileNotFoundError, for one not there).")
        .def_static(
            "from_dict",
            [](const py::dict& scene, const std::optional<PathArg>& base,
               const std::optional<SettingsArg>& settings) {
                const std::string folder =
                    base ? pathFrom(base->value, "base")
                         : py::module_::import("os").attr("getcwd")().cast<std::string>();
                return made(kDictName, jsonOf(scene, folder),
                            settings ? checkedOverrides(settings->value) : SettingOverrides{});
            },
            py::arg("scene"), py::arg("base") = py::none(), py::arg("settings") = py::none(),
            "A scene from a dict of the scene file's schema (docs/scene-format.md), checked as a "
            "file is (messages name it '<dict>'); its glTF paths are relative to `base` (None: "
            "the working folder).")
        .def_property(
            "settings", [](const std::shared_ptr<SceneObject>& s) { return settingsOf(s); },
            [](const std::shared_ptr<SceneObject>& s, const SettingsArg& mapping) {
                setSettings(s, mapping.value);
            },
            "The method settings (an ssgi.Settings mapping); assigning a dict changes the settings "
            "it names, every one checked before any is applied.")
        .def_property_readonly(
            "path", [](const SceneObject& s) { return s.path; },
            "The scene's file, as given ('<dict>' for a scene from a dict).")
        .def_property_readonly(
            "animated",
            [](const SceneObject& s) {
                return !s.scene->cameraPath.empty() || !s.scene->objectPaths.empty();
            },
            "Whether the scene has a camera path or object paths (set_time moves along them).")
        .def(
            "__copy__",
            [](const SceneObject& s) {
                auto copy = std::make_shared<SceneObject>(s); // shares the scene until a change
                return copy;
            },
            "A scene of its own (a change of either leaves the other as it is).")
        .def(
            "__deepcopy__",
            [](const SceneObject& s, const py::object&) {
                return std::make_shared<SceneObject>(s);
            },
            py::arg("memo"), "As __copy__: the loaded scene is shared until either changes.")
        .def(py::pickle(
            [](const SceneObject& s) {
                py::dict overrides;
                for (const auto& [name, value] : s.overrides)
                    overrides[py::str(name)] = value;
                return py::make_tuple(s.path, s.json, overrides);
            },
            [](const py::tuple& state) {
                if (state.size() != 3) throw InputError("Scene: not a pickled ssgi.Scene");
                return made(state[0].cast<std::string>(), state[1].cast<std::string>(),
                            checkedOverrides(state[2]));
            }))
        .def(
            "__repr__",
            [](const SceneObject& s) {
                const py::object table = settingsOf(std::make_shared<SceneObject>(s)).value;
                std::string changed;
                for (const auto& [name, value] : s.overrides)
                    changed += (changed.empty() ? "" : ", ") +
                               std::string(py::repr(py::str(name))) + ": " +
                               std::string(py::repr(table[py::str(name)]));
                const std::string what =
                    s.json.empty() ? std::string(py::repr(py::str(s.path))) : "<dict>";
                return "ssgi.Scene(" + what +
                       (changed.empty() ? "" : ", settings={" + changed + "}") + ")";
            },
            "ssgi.Scene(path, settings={...}) with the settings given from Python.");
}

} // namespace ssgi::python
