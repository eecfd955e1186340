// ssgi.Scene and its settings, a mapping over the settings table (renderer/scene/settings.h):
// each value of the table's type, each change checked as a scene file's or --set's is.
#include "module.h"

#include "scene/settings.h"

#include <pybind11/stl.h>

#include <cmath>
#include <sstream>

namespace ssgi::python {

namespace {

const SettingRow* rowNamed(const std::string& name) {
    for (const SettingRow& row : settingTable())
        if (name == row.name) return &row;
    return nullptr;
}

py::object typed(const SettingRow& row, double value) {
    if (row.flag()) return py::bool_(value != 0.0);
    if (row.whole()) return py::int_(static_cast<long long>(value));
    return py::float_(value);
}

// A Python value for a setting, as a number, checked against the table's range. The message of
// a bad one is --set's with "settings" in its place. NumPy's numbers count as the Python numbers
// they equal.
double checkedValue(const std::string& name, const py::handle& given) {
    const py::object value = plainNumber(given, "settings: setting '" + name + "'");
    if (!py::isinstance<py::bool_>(value) && !py::isinstance<py::int_>(value) &&
        !py::isinstance<py::float_>(value)) {
        if (!rowNamed(name)) checkSetting("settings", name, 0.0); // the unknown name's message
        throw py::type_error("settings: setting '" + name + "' must be a number or a bool, not " +
                             std::string(py::repr(given)) + " (" + typeName(given) + ")");
    }
    if (py::isinstance<py::int_>(value) && !py::isinstance<py::bool_>(value)) {
        // An int no double equals is beyond every setting's range: said as it was given.
        const SettingRow* row = rowNamed(name);
        bool exact = false;
        try {
            exact = value.equal(py::float_(value));
        } catch (const py::error_already_set&) { // beyond a double's range
        }
        if (!exact) {
            std::ostringstream problem; // --set's message, the value as given
            problem << "settings: setting '" << name << "' is " << std::string(py::str(value))
                    << ", outside [" << row->min << ", " << row->max << "]";
            throw InputError(problem.str());
        }
    }
    return checkSetting("settings", name, value.cast<double>());
}

Scene load(const std::string& path, const SettingOverrides& overrides) {
    py::gil_scoped_release release;
    return loadScene(path, overrides);
}

// Applies checked values. The ones read while loading (ground_plane, and an ao_radius of 0, which
// the loader derives from the model) load the scene again, as --set would have given them.
void applySettings(SceneObject& s, const SettingOverrides& values) {
    SettingOverrides overrides = s.overrides;
    bool reload = false;
    for (const auto& [name, value] : values) {
        reload = reload || (name == "ground_plane" && value != s.scene->settings.ground_plane) ||
                 (name == "ao_radius" && value == 0.0);
        overrides[name] = value;
    }
    if (reload) {
        s.scene = std::make_shared<Scene>(load(s.path, overrides));
    } else {
        Scene& scene = s.writable();
        scene.settings = withOverrides(scene.settings, values, "settings");
    }
    s.overrides = std::move(overrides);
}

struct SettingsView {
    std::shared_ptr<SceneObject> owner;
};

py::dict asDict(const SceneObject& s) {
    py::dict d;
    for (const SettingRow& row : settingTable())
        d[row.name] = typed(row, row.get(s.scene->settings));
    return d;
}

void update(SceneObject& s, const py::handle& mapping) {
    if (!py::isinstance<py::dict>(mapping) && !py::hasattr(mapping, "items"))
        throw py::type_error("settings: expected a mapping of setting names to values, got " +
                             typeName(mapping));
    SettingOverrides values; // every one checked before any is applied
    for (const py::handle item : mapping.attr("items")()) {
        const py::tuple pair = py::reinterpret_borrow<py::tuple>(item);
        if (!py::isinstance<py::str>(pair[0]))
            throw py::type_error("settings: a setting's name must be a str, not " +
                                 typeName(pair[0]));
        const std::string name = pair[0].cast<std::string>();
        values[name] = checkedValue(name, pair[1]);
    }
    applySettings(s, values);
}

} // namespace

Scene& SceneObject::writable() {
    if (scene.use_count() > 1) scene = std::make_shared<Scene>(*scene);
    return *scene;
}

SceneObject& sceneArg(const std::shared_ptr<SceneObject>& scene) {
    if (!scene) throw py::type_error("scene: expected an ssgi.Scene, got None");
    return *scene;
}

void defineScene(py::module_& m) {
    py::class_<SettingsView>(m, "Settings",
                             "The scene's method settings by name (docs/settings.md), a mapping: "
                             "read, assign and update() like a dict. Each value is of the "
                             "table's type (bool, int, float); Python and NumPy numbers are "
                             "taken, each checked against the setting's range.")
        .def(
            "__getitem__",
            [](const SettingsView& v, const std::string& name) {
                const SettingRow* row = rowNamed(name);
                if (!row) throw py::key_error(name);
                return SettingValue{typed(*row, row->get(v.owner->scene->settings))};
            },
            py::arg("name"), "The setting's value; KeyError for a name not in the table.")
        .def(
            "__setitem__",
            [](SettingsView& v, const std::string& name, const SettingValue& value) {
                applySettings(*v.owner, {{name, checkedValue(name, value.value)}});
                raiseWarnings();
            },
            py::arg("name"), py::arg("value"),
            "Sets one setting, checked as --set checks it (ValueError out of range).")
        .def(
            "__contains__",
            [](const SettingsView&, const py::object& name) {
                return py::isinstance<py::str>(name) && rowNamed(name.cast<std::string>());
            },
            py::arg("name"), "Whether the settings table has this name.")
        .def(
            "__len__", [](const SettingsView&) { return settingTable().size(); },
            "The number of settings.")
        .def(
            "__iter__", [](const SettingsView& v) { return py::iter(asDict(*v.owner)); },
            "The settings' names, in the table's order.")
        .def(
            "keys", [](const SettingsView& v) { return asDict(*v.owner).attr("keys")(); },
            "The settings' names.")
        .def(
            "values", [](const SettingsView& v) { return asDict(*v.owner).attr("values")(); },
            "The settings' values.")
        .def(
            "items", [](const SettingsView& v) { return asDict(*v.owner).attr("items")(); },
            "The (name, value) pairs.")
        .def(
            "get",
            [](const SettingsView& v, const std::string& name, py::object fallback) {
                const SettingRow* row = rowNamed(name);
                return row ? typed(*row, row->get(v.owner->scene->settings)) : fallback;
            },
            py::arg("name"), py::arg("default") = py::none(),
            "The setting's value, or `default` for a name not in the table.")
        .def(
            "update",
            [](SettingsView& v, const SettingsArg& mapping) {
                update(*v.owner, mapping.value);
                raiseWarnings();
            },
            py::arg("values"),
            "Sets the settings a mapping names, every value checked before any is applied.")
        .def(
            "to_dict", [](const SettingsView& v) { return asDict(*v.owner); },
            "A dict of every setting's current value.")
        .def(
            "__eq__",
            [](const SettingsView& v, const py::object& other) {
                return asDict(*v.owner).equal(other);
            },
            py::arg("other"), "Whether `other` (a mapping) holds the same values.")
        .def(
            "__repr__", [](const SettingsView& v) { return py::repr(asDict(*v.owner)); },
            "The settings as a dict's repr.");

    py::class_<SceneObject, std::shared_ptr<SceneObject>>(
        m, "Scene",
        "A scene file (.json) or a bare glTF (.gltf, .glb), loaded as the programs load it. "
        "`settings` (a mapping) overrides method settings as --set does.")
        .def(py::init([](const PathArg& path, const std::optional<SettingsArg>& settings) {
                 auto s = std::make_shared<SceneObject>();
                 s->path = pathFrom(path.value, "path");
                 if (settings && !settings->value.is_none()) {
                     if (!py::hasattr(settings->value, "items"))
                         throw py::type_error("settings: expected a mapping of setting names "
                                              "to values, got " +
                                              typeName(settings->value));
                     for (const py::handle item : settings->value.attr("items")()) {
                         const py::tuple pair = py::reinterpret_borrow<py::tuple>(item);
                         const std::string name = py::str(pair[0]);
                         s->overrides[name] = checkedValue(name, pair[1]);
                     }
                 }
                 s->scene = std::make_shared<Scene>(load(s->path, s->overrides));
                 raiseWarnings();
                 return s;
             }),
             py::arg("path"), py::arg("settings") = py::none(),
             "Loads the scene at `path` (str or os.PathLike) with `settings` overriding the "
             "method settings, as render --set does; ssgi.InputError with render's message for "
             "a file it refuses.")
        .def_property(
            "settings", [](const std::shared_ptr<SceneObject>& s) { return SettingsView{s}; },
            [](const std::shared_ptr<SceneObject>& s, const SettingsArg& mapping) {
                update(*s, mapping.value);
                raiseWarnings();
            },
            "The method settings (an ssgi.Settings mapping); assigning a dict changes the settings "
            "it names, every one checked before any is applied.")
        .def_property_readonly(
            "path", [](const SceneObject& s) { return s.path; }, "The scene's file, as given.")
        .def_property_readonly(
            "animated",
            [](const SceneObject& s) {
                return !s.scene->cameraPath.empty() || !s.scene->objectPaths.empty();
            },
            "Whether the scene has a camera path or object paths (set_time moves along them).")
        .def(
            "__repr__",
            [](const SceneObject& s) {
                std::string changed;
                for (const auto& [name, value] : s.overrides) {
                    const SettingRow* row = rowNamed(name);
                    changed += (changed.empty() ? "" : ", ") +
                               std::string(py::repr(py::str(name))) + ": " +
                               std::string(py::repr(typed(*row, value)));
                }
                return "ssgi.Scene(" + std::string(py::repr(py::str(s.path))) +
                       (changed.empty() ? "" : ", settings={" + changed + "}") + ")";
            },
            "ssgi.Scene(path, settings={...}) with the settings given from Python.");

    m.def(
        "settings_table",
        [] {
            py::list rows;
            for (const SettingRow& row : settingTable()) {
                py::dict d;
                d["name"] = row.name;
                d["type"] = row.type;
                d["default"] = typed(row, row.defaultValue);
                d["min"] = row.min;
                d["max"] = row.max;
                d["group"] = row.group;
                d["meaning"] = row.meaning;
                rows.append(d);
            }
            return rows;
        },
        "Every method setting as a dict: name, type, default, min, max, group and meaning "
        "(docs/settings.md).");
}

} // namespace ssgi::python
