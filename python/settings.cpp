// ssgi.Settings, a collections.abc.MutableMapping over the settings table
// (renderer/scene/settings.h): each value of the table's type, each change checked as a scene
// file's or --set's is; and settings_table().
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

// A name the table lacks: its message is --set's (the known names), as a KeyError too.
const SettingRow& knownRow(const std::string& name) {
    const SettingRow* row = rowNamed(name);
    if (row) return *row;
    try {
        checkSetting("settings", name, 0.0);
    } catch (const InputError& e) {
        throw SettingNameError(e.what());
    }
    throw SettingNameError("settings: unknown setting '" + name + "'");
}

// A Python value for a setting, as a number, checked against the table's range. The message of
// a bad one is --set's with "settings" in its place. NumPy's numbers count as the Python numbers
// they equal.
double checkedValue(const std::string& name, const py::handle& given) {
    const py::object value = plainNumber(given, "settings: setting '" + name + "'");
    if (!py::isinstance<py::bool_>(value) && !py::isinstance<py::int_>(value) &&
        !py::isinstance<py::float_>(value)) {
        knownRow(name); // the unknown name's message
        throw ArgumentTypeError("settings: setting '" + name +
                                "' must be a number or a bool, not " +
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
    knownRow(name);
    return checkSetting("settings", name, value.cast<double>());
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
        s.scene = std::make_shared<Scene>(loadSceneObject(s, overrides));
        ++s.loads;
    } else {
        Scene& scene = s.writable();
        scene.settings = withOverrides(scene.settings, values, "settings");
    }
    s.overrides = std::move(overrides);
}

struct SettingsView {
    std::shared_ptr<SceneObject> owner;
};

// Forgets what Python set of `names` (all: every one): the scene loads again with the rest, so
// each of them is the scene file's value again.
void forget(SceneObject& s, const std::vector<std::string>& names, bool all) {
    SettingOverrides overrides = all ? SettingOverrides{} : s.overrides;
    for (const std::string& name : names)
        overrides.erase(name);
    if (overrides.size() == s.overrides.size() && !all) return;
    s.scene = std::make_shared<Scene>(loadSceneObject(s, overrides));
    ++s.loads;
    s.overrides = std::move(overrides);
}

py::object valueOf(const SceneObject& s, const std::string& name) {
    const SettingRow& row = knownRow(name);
    return typed(row, row.get(s.scene->settings));
}

py::dict asDict(const SceneObject& s) {
    py::dict d;
    for (const SettingRow& row : settingTable())
        d[row.name] = typed(row, row.get(s.scene->settings));
    return d;
}

} // namespace

SettingOverrides checkedOverrides(const py::handle& mapping) {
    SettingOverrides values; // every one checked before any is applied
    if (mapping.is_none()) return values;
    const bool pairs = !py::hasattr(mapping, "items");
    if (pairs && (py::isinstance<py::str>(mapping) || !py::hasattr(mapping, "__iter__")))
        throw ArgumentTypeError("settings: expected a mapping of setting names to values, got " +
                                std::string(py::repr(mapping)) + " (" + typeName(mapping) + ")");
    for (const py::handle item : pairs ? py::iter(mapping) : py::iter(mapping.attr("items")())) {
        py::tuple pair;
        try {
            pair = py::tuple(py::reinterpret_borrow<py::object>(item));
        } catch (const py::error_already_set&) {
        }
        if (!pair || pair.size() != 2)
            throw ArgumentTypeError("settings: expected (name, value) pairs, got " +
                                    std::string(py::repr(item)));
        if (!py::isinstance<py::str>(pair[0]))
            throw ArgumentTypeError("settings: a setting's name must be a str, not " +
                                    std::string(py::repr(pair[0])) + " (" + typeName(pair[0]) +
                                    ")");
        const std::string name = pair[0].cast<std::string>();
        values[name] = checkedValue(name, pair[1]);
    }
    return values;
}

SettingsResult settingsOf(const std::shared_ptr<SceneObject>& owner) {
    return {py::cast(SettingsView{owner})};
}

void setSettings(const std::shared_ptr<SceneObject>& owner, const py::handle& mapping) {
    applySettings(sceneArg(owner), checkedOverrides(mapping));
    raiseWarnings();
}

void defineSettings(py::module_& m) {
    using V = SettingsView;
    py::class_<V>(m, "Settings",
                  "The scene's method settings by name (docs/settings.md), a "
                  "collections.abc.MutableMapping: read, assign, update() and del like a dict's. "
                  "Each value is of the table's type (bool, int, float); Python and NumPy numbers "
                  "are taken, each checked against the setting's range. A name the table lacks is "
                  "an ssgi.SettingNameError (a KeyError). del forgets what Python set: the "
                  "setting is the scene file's again.")
        .def(
            "__getitem__",
            [](const V& v, const std::string& name) {
                return SettingResult{valueOf(*v.owner, name)};
            },
            py::arg("name"),
            "The setting's value; ssgi.SettingNameError (a KeyError) for a name "
            "not in the table.")
        .def(
            "__setitem__",
            [](V& v, const std::string& name, const SettingValue& value) {
                applySettings(*v.owner, {{name, checkedValue(name, value.value)}});
                raiseWarnings();
            },
            py::arg("name"), py::arg("value"),
            "Sets one setting, checked as --set checks it (ssgi.InputError out of range).")
        .def(
            "__delitem__",
            [](V& v, const std::string& name) {
                knownRow(name);
                forget(*v.owner, {name}, false);
                raiseWarnings();
            },
            py::arg("name"), "Forgets what Python set of the setting: the scene file's value.")
        .def(
            "__contains__",
            [](const V&, const py::object& name) {
                return py::isinstance<py::str>(name) && rowNamed(name.cast<std::string>());
            },
            py::arg("name"), "Whether the settings table has this name.")
        .def(
            "__len__", [](const V&) { return settingTable().size(); }, "The number of settings.")
        .def(
            "__iter__", [](const V& v) { return NamesIterator{py::iter(asDict(*v.owner))}; },
            "The settings' names, in the table's order.")
        .def(
            "keys", [](const V& v) { return KeysResult{asDict(*v.owner).attr("keys")()}; },
            "The settings' names.")
        .def(
            "values", [](const V& v) { return ValuesResult{asDict(*v.owner).attr("values")()}; },
            "The settings' values.")
        .def(
            "items", [](const V& v) { return ItemsResult{asDict(*v.owner).attr("items")()}; },
            "The (name, value) pairs.")
        .def(
            "get",
            [](const V& v, const std::string& name, py::object fallback) {
                return AnyResult{rowNamed(name) ? valueOf(*v.owner, name) : fallback};
            },
            py::arg("name"), py::arg("default") = py::none(),
            "The setting's value, or `default` for a name not in the table.")
        .def(
            "pop",
            [](V& v, const std::string& name, const py::object&) {
                const py::object value = valueOf(*v.owner, name);
                forget(*v.owner, {name}, false);
                raiseWarnings();
                return SettingResult{value};
            },
            py::arg("name"), py::arg("default") = py::none(),
            "The setting's value, forgetting what Python set of it (as del).")
        .def(
            "popitem",
            [](V& v) {
                if (v.owner->overrides.empty())
                    throw py::key_error("popitem(): no setting was set from Python");
                const std::string name = v.owner->overrides.rbegin()->first;
                const py::object value = valueOf(*v.owner, name);
                forget(*v.owner, {name}, false);
                raiseWarnings();
                return py::make_tuple(name, value);
            },
            "Forgets one setting set from Python and returns it with the value it had; KeyError "
            "when none was.")
        .def(
            "clear",
            [](V& v) {
                forget(*v.owner, {}, true);
                raiseWarnings();
            },
            "Forgets every setting set from Python: the scene file's values.")
        .def(
            "setdefault",
            [](const V& v, const std::string& name, const py::object&) {
                return SettingResult{valueOf(*v.owner, name)};
            },
            py::arg("name"), py::arg("default") = py::none(),
            "The setting's value (every setting has one).")
        .def(
            "update",
            [](V& v, const py::object& values, const py::kwargs& named) {
                SettingOverrides all = checkedOverrides(values);
                for (const auto& [name, value] : checkedOverrides(named))
                    all[name] = value;
                applySettings(*v.owner, all);
                raiseWarnings();
            },
            py::arg("values") = py::none(),
            "Sets the settings a mapping (or (name, value) pairs, or keywords) names, every value "
            "checked before any is applied.")
        .def(
            "to_dict", [](const V& v) { return asDict(*v.owner); },
            "A dict of every setting's current value.")
        .def(
            "__eq__",
            [](const V& v, const py::object& other) {
                if (py::isinstance<V>(other))
                    return asDict(*v.owner).equal(asDict(*other.cast<V&>().owner));
                return asDict(*v.owner).equal(other);
            },
            py::arg("other"), "Whether `other` (a mapping) holds the same values.")
        .def(
            "__repr__", [](const V& v) { return py::repr(asDict(*v.owner)); },
            "The settings as a dict's repr.");
    // A real MutableMapping for isinstance (its methods are the ones above).
    py::module_::import("collections.abc")
        .attr("MutableMapping")
        .attr("register")(m.attr("Settings"));

    m.def(
        "settings_table",
        [] {
            py::list rows;
            for (const SettingRow& row : settingTable()) {
                py::dict d;
                d["name"] = row.name;
                d["type"] = row.flag() ? "bool" : row.whole() ? "int" : "float"; // Python's
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
