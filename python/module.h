// What the Python module's source files share: converting between NumPy arrays and the
// programs' images, reading arguments the way the programs read theirs, and the parts of the
// module each file defines.
#pragma once

#include "metrics/metrics.h"
#include "scene/scene.h"

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace ssgi::python {

namespace py = pybind11;

// An argument of the wrong type: ssgi.ArgumentTypeError (a TypeError), as InputError is
// ssgi.InputError (a ValueError). The module's exceptions and their classes: module.cpp.
struct ArgumentTypeError : std::runtime_error {
    using std::runtime_error::runtime_error;
};
// A setting's name the table lacks: ssgi.SettingNameError (a KeyError and an InputError).
struct SettingNameError : InputError {
    using InputError::InputError;
};

// Arguments taken as any Python object and checked by the function with the programs' messages
// (NumPy scalars included), but shown in signatures and help() as the type they must hold.
struct ObjectArg {
    py::object value;
};
struct IntArg : ObjectArg {};         // int: a Python or NumPy integer, or a 0-d array of one
struct FloatArg : ObjectArg {};       // float: any real number, exactly a double
struct PathArg : ObjectArg {};        // str or os.PathLike
struct SizeArg : ObjectArg {};        // (width, height), or an image whose size it is
struct Vec3Arg : ObjectArg {};        // (x, y, z)
struct ImageArg : ObjectArg {};       // an array of shape (h, w), (h, w, 1), (h, w, 3) or (h, w, 4)
struct ImageOrPathArg : ObjectArg {}; // an image, or the path of an image file
struct ProgressArg : ObjectArg {};    // None, a bool or a callable
struct SettingsArg : ObjectArg {};    // a mapping of setting names to values
struct SettingValue : ObjectArg {};   // a setting's value: bool, int or float (NumPy's too)
struct SettingResult : ObjectArg {};  // a setting's value as read: bool, int or float
struct NamesArg : ObjectArg {};       // a list of names
struct BoolArg : ObjectArg {};        // True or False (NumPy's too)
struct ImageResult : ObjectArg {};    // an ssgi.Image (imageObject)
// What the Settings mapping returns, typed as the stub types it.
struct SettingsResult : ObjectArg {}; // an ssgi.Settings
struct KeysResult : ObjectArg {};
struct ValuesResult : ObjectArg {};
struct ItemsResult : ObjectArg {};
struct NamesIterator : ObjectArg {};
struct AnyResult : ObjectArg {};

// H x W x 3 float32 over RGBA floats: the vector moves into the array's owner, and the array
// views its RGB, so the pixels are not copied again.
py::array rgbArray(std::vector<float>&& rgba, uint32_t width, uint32_t height);
// H x W x 4, all four channels.
py::array rgbaArray(std::vector<float>&& rgba, uint32_t width, uint32_t height);
// H x W float64 of a per-pixel map.
py::array mapArray(const std::vector<double>& map, uint32_t width, uint32_t height);

// An array as an ssgi.Image (python/ssgi/_image.py): a NumPy array that shows itself in a
// notebook, and what a reference records of itself (its samples per pixel, its noise).
ImageResult imageObject(const py::object& array, std::optional<double> noise = std::nullopt,
                        std::optional<uint32_t> samples = std::nullopt);
// The composite's display transform of every colour channel (tonemap(), write_image's PNG).
void displayEncode(metrics::Image& image, float exposure);

// An array of numbers of shape (h, w), (h, w, 1), (h, w, 3) or (h, w, 4) as RGBA floats (grey
// as R = G = B, alpha 1 where it has none): floats as they are, uint8 scaled by 1/255, uint16
// by 1/65535. InputError naming `what` for anything else, TypeError for what is not an array.
metrics::Image imageFrom(const py::handle& array, const std::string& what);
// Whether `array` holds integers (display values, as an 8- or 16-bit file stores them).
bool holdsIntegers(const py::handle& array);

// A file path given as str or os.PathLike: TypeError for anything else, ValueError for a NUL
// character in it, each naming the argument `what`.
std::string pathFrom(const py::handle& path, const std::string& what);
bool isPath(const py::handle& object);

// A Python or NumPy scalar, or a 0-d array, as the Python bool, int or float it equals exactly;
// anything else as it is (for the caller to refuse by its type). ValueError for a number that no
// double equals (a long double, a Fraction).
py::object plainNumber(const py::handle& value, const std::string& what);
std::string typeName(const py::handle& value);

// A number checked as the programs check their options: InputError "<name>: '<value>' is not a
// number in [lo, hi]" (cli::parseNumber), or "... is not a whole number ..." (cli::parseCount).
double numberArg(const std::string& name, const py::handle& value, double lo, double hi);
uint32_t countArg(const std::string& name, const py::handle& value, uint32_t lo, uint32_t hi);
// (width, height), each in lo..hi.
void sizeArg(const py::handle& size, uint32_t& width, uint32_t& height, uint32_t lo, uint32_t hi);
// True, False (or NumPy's), else TypeError naming `name`.
bool boolArg(const std::string& name, const py::handle& value);

// The library's warnings (warn()) said since the last call, as Python warnings of the category
// ssgi.SsgiWarning. Call with the GIL held, after the C++ code ran; throws error_already_set
// when a filter makes a warning an error.
void raiseWarnings();

// A scene as Python holds it: loaded from a file, or from a dict (its JSON text). A renderer
// made from it shares the loaded scene; a later change copies the scene first (copy on write),
// so the renderer sees a new scene at its next frame and applies it (renderer.cpp).
struct SceneObject {
    std::string path; // the file, or "<dict>" for a scene made from a dict
    std::string json; // a dict's scene as JSON (its glTF paths absolute); empty for a file
    SettingOverrides overrides; // the settings given from Python, kept for a reload
    std::shared_ptr<Scene> scene;
    // Times the scene was loaded again (a setting read while loading, or one forgotten); a
    // change between two loads is of its settings alone, its geometry the same.
    uint64_t loads = 0;
    Scene& writable();
};
// Loads (again) the scene as `s` names it, with `overrides` (scene.cpp).
Scene loadSceneObject(const SceneObject& s, const SettingOverrides& overrides);
// The scene argument of a function: TypeError for None (which pybind11 lets through).
SceneObject& sceneArg(const std::shared_ptr<SceneObject>& scene);

// The scene's settings as Python reads them (scene.cpp): ssgi.Settings of `owner`.
SettingsResult settingsOf(const std::shared_ptr<SceneObject>& owner);
void setSettings(const std::shared_ptr<SceneObject>& owner, const py::handle& mapping);

void defineErrors(py::module_& m);
void defineScene(py::module_& m);
void defineRenderer(py::module_& m);
void defineDevices(py::module_& m);
void defineImages(py::module_& m);

} // namespace ssgi::python

namespace pybind11::detail {

// Takes any object; the function checks it. `Name` is what signatures show.
template <class T> struct object_arg_caster {
    bool load(handle src, bool) {
        value.value = reinterpret_borrow<object>(src);
        return true;
    }
    static handle cast(const T& src, return_value_policy, handle) { return src.value.inc_ref(); }
    T value;
    operator T*() { return &value; }
    operator T&() { return value; }
    operator T&&() && { return std::move(value); }
    template <typename U> using cast_op_type = movable_cast_op_type<U>;
};

#define SSGI_OBJECT_ARG(Type, Name)                                                                \
    template <> struct type_caster<ssgi::python::Type> : object_arg_caster<ssgi::python::Type> {   \
        static constexpr auto name = const_name(Name);                                             \
    };

// The names are the stub's (python/ssgi/__init__.pyi): as wide as what the checks accept, NumPy's
// numbers included, so that a type checker takes what the module takes.
#define SSGI_INT "Union[int, numpy.integer]"
#define SSGI_FLOAT "Union[float, numpy.floating, numpy.integer]"
#define SSGI_BOOL "Union[bool, numpy.bool_]"
#define SSGI_VALUE "Union[bool, int, float, numpy.bool_, numpy.integer, numpy.floating]"
SSGI_OBJECT_ARG(IntArg, SSGI_INT)
SSGI_OBJECT_ARG(FloatArg, SSGI_FLOAT)
SSGI_OBJECT_ARG(PathArg, "Union[str, os.PathLike]")
SSGI_OBJECT_ARG(SizeArg, "Union[Tuple[" SSGI_INT ", " SSGI_INT "], numpy.ndarray]")
SSGI_OBJECT_ARG(Vec3Arg, "Union[Sequence[" SSGI_FLOAT "], numpy.ndarray]")
SSGI_OBJECT_ARG(ImageArg, "numpy.ndarray")
SSGI_OBJECT_ARG(ImageOrPathArg, "Union[numpy.ndarray, str, os.PathLike]")
SSGI_OBJECT_ARG(ProgressArg, "Union[bool, Callable[[float, int, float], object], None]")
SSGI_OBJECT_ARG(SettingsArg, "Mapping[str, " SSGI_VALUE "]")
SSGI_OBJECT_ARG(SettingValue, SSGI_VALUE)
SSGI_OBJECT_ARG(SettingResult, "Union[bool, int, float]")
SSGI_OBJECT_ARG(NamesArg, "Sequence[str]")
SSGI_OBJECT_ARG(BoolArg, SSGI_BOOL)
SSGI_OBJECT_ARG(ImageResult, "ssgi.Image")
SSGI_OBJECT_ARG(SettingsResult, "ssgi.Settings")
SSGI_OBJECT_ARG(KeysResult, "KeysView[str]")
SSGI_OBJECT_ARG(ValuesResult, "ValuesView[Union[bool, int, float]]")
SSGI_OBJECT_ARG(ItemsResult, "ItemsView[str, Union[bool, int, float]]")
SSGI_OBJECT_ARG(NamesIterator, "Iterator[str]")
SSGI_OBJECT_ARG(AnyResult, "Any")
#undef SSGI_OBJECT_ARG

} // namespace pybind11::detail
