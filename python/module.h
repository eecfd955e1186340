// What the Python module's source files share: converting between NumPy arrays and the
// programs' images, reading arguments the way the programs read theirs, and the parts of the
// module each file defines.
#pragma once

#include "metrics/metrics.h"
#include "scene/scene.h"

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <memory>
#include <string>
#include <vector>

namespace ssgi::python {

namespace py = pybind11;

// H x W x 3 float32 over RGBA floats: the vector moves into the array's owner, and the array
// views its RGB, so the pixels are not copied again.
py::array rgbArray(std::vector<float>&& rgba, uint32_t width, uint32_t height);
// H x W x 4, all four channels.
py::array rgbaArray(std::vector<float>&& rgba, uint32_t width, uint32_t height);
// H x W float64 of a per-pixel map.
py::array mapArray(const std::vector<double>& map, uint32_t width, uint32_t height);

// An H x W x 3 or H x W x 4 array of numbers as RGBA floats (alpha 1 where it has none);
// InputError naming `what` for anything else.
metrics::Image imageFrom(const py::handle& array, const std::string& what);

// A file path given as str or os.PathLike.
std::string pathFrom(const py::handle& path);
bool isPath(const py::handle& object);

// A number checked as the programs check their options: InputError "<name>: '<value>' is not a
// number in [lo, hi]" (cli::parseNumber), or "... is not a whole number ..." (cli::parseCount).
double numberArg(const std::string& name, const py::handle& value, double lo, double hi);
uint32_t countArg(const std::string& name, const py::handle& value, uint32_t lo, uint32_t hi);
// (width, height), each in lo..hi.
void sizeArg(const py::handle& size, uint32_t& width, uint32_t& height, uint32_t lo, uint32_t hi);

// A scene as Python holds it. A renderer made from it shares the loaded scene and keeps it as
// it was: a later change of a setting copies the scene first (copy on write).
struct SceneObject {
    std::string path;
    SettingOverrides overrides; // the settings given from Python, kept for a reload
    std::shared_ptr<Scene> scene;
    Scene& writable();
};

void defineScene(py::module_& m);
void defineRenderer(py::module_& m);
void defineImages(py::module_& m);

} // namespace ssgi::python
