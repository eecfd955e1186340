// ssgi.Scene and its settings, a mapping over the settings table (renderer/scene/settings.h):
// each value of the table's type, each change checked as a scene file's or --set's is.
#include "module.h"

#include "scene/settings.h"

#include <pybind11/stl.h>

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
// a bad one is --set's with "settings" in its place.
double checkedValue(const std::string& name, const py::handle& value) {
    const bool number = py::isinstance<py::bool_>(value) || py::isinstance<py::int_>(value) ||
                        py::isinstance<py::float_>(value);
    if (!number) {
        checkSetting("settings", name, 0.0); // an unknown name's message first
        throw InputError("settings: setting '" + name + "' must be a number or a bool, not " +
                         std::string(py::str(py::type::of(value).attr("__name__"))));
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
        throw InputError("settings: expected a mapping of setting names to values");
    SettingOverrides values; // every one checked before any is applied
    for (const py::handle item : mapping.attr("items")()) {
        const py::tuple pair = py::reinterpret_borrow<py::tuple>(item);
        if (!py::isinstance<py::str>(pair[0]))
            throw InputError("settings: a setting's name must be a str");
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

void defineScene(py::module_& m) {
    py::class_<SettingsView>(m, "Settings",
                             "The scene's method settings by name (docs/settings.md), a "
                             "mapping: read, assign and update() like a dict.")
        .def("__getitem__",
             [](const SettingsView& v, const std::string& name) {
                 const SettingRow* row = rowNamed(name);
                 if (!row) throw py::key_error(name);
                 return typed(*row, row->get(v.owner->scene->settings));
             })
        .def("__setitem__",
             [](SettingsView& v, const std::string& name, const py::object& value) {
                 applySettings(*v.owner, {{name, checkedValue(name, value)}});
             })
        .def("__contains__",
             [](const SettingsView&, const py::object& name) {
                 return py::isinstance<py::str>(name) && rowNamed(name.cast<std::string>());
             })
        .def("__len__", [](const SettingsView&) { return settingTable().size(); })
        .def("__iter__", [](const SettingsView& v) { return py::iter(asDict(*v.owner)); })
        .def("keys", [](const SettingsView& v) { return asDict(*v.owner).attr("keys")(); })
        .def("values", [](const SettingsView& v) { return asDict(*v.owner).attr("values")(); })
        .def("items", [](const SettingsView& v) { return asDict(*v.owner).attr("items")(); })
        .def(
            "get",
            [](const SettingsView& v, const std::string& name, py::object fallback) {
                const SettingRow* row = rowNamed(name);
                return row ? typed(*row, row->get(v.owner->scene->settings)) : fallback;
            },
            py::arg("name"), py::arg("default") = py::none())
        .def("update",
             [](SettingsView& v, const py::object& mapping) { update(*v.owner, mapping); })
        .def("to_dict", [](const SettingsView& v) { return asDict(*v.owner); })
        .def("__eq__", [](const SettingsView& v,
                          const py::object& other) { return asDict(*v.owner).equal(other); })
        .def("__repr__", [](const SettingsView& v) { return py::repr(asDict(*v.owner)); });

    py::class_<SceneObject, std::shared_ptr<SceneObject>>(
        m, "Scene",
        "A scene file (.json) or a bare glTF (.gltf, .glb), loaded as the programs load it. "
        "`settings` (a mapping) overrides method settings as --set does.")
        .def(py::init([](const py::object& path, const py::object& settings) {
                 auto s = std::make_shared<SceneObject>();
                 s->path = pathFrom(path);
                 if (!settings.is_none()) {
                     if (!py::hasattr(settings, "items"))
                         throw InputError(
                             "settings: expected a mapping of setting names to values");
                     for (const py::handle item : settings.attr("items")()) {
                         const py::tuple pair = py::reinterpret_borrow<py::tuple>(item);
                         const std::string name = py::str(pair[0]);
                         s->overrides[name] = checkedValue(name, pair[1]);
                     }
                 }
                 s->scene = std::make_shared<Scene>(load(s->path, s->overrides));
                 return s;
             }),
             py::arg("path"), py::arg("settings") = py::none())
        .def_property(
            "settings", [](const std::shared_ptr<SceneObject>& s) { return SettingsView{s}; },
            [](const std::shared_ptr<SceneObject>& s, const py::object& mapping) {
                update(*s, mapping);
            },
            "The method settings (an ssgi.Settings mapping); assigning a dict changes the settings "
            "it names, every one checked before any is applied.")
        .def_property_readonly("path", [](const SceneObject& s) { return s.path; })
        .def_property_readonly("animated",
                               [](const SceneObject& s) {
                                   return !s.scene->cameraPath.empty() ||
                                          !s.scene->objectPaths.empty();
                               })
        .def("__repr__", [](const SceneObject& s) { return "ssgi.Scene('" + s.path + "')"; });

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
        "Every method setting: name, type, default, range, group and meaning (docs/settings.md).");
}

} // namespace ssgi::python
