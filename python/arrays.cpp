#include "app/cli.h"
#include "module.h"
#include "scene/scene.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>

namespace ssgi::python {

namespace {

py::array viewOf(std::vector<float>&& rgba, uint32_t width, uint32_t height, size_t channels) {
    auto* owned = new std::vector<float>(std::move(rgba));
    py::capsule owner(owned, [](void* p) { delete static_cast<std::vector<float>*>(p); });
    const py::ssize_t pixel = 4 * sizeof(float);
    return py::array(
        py::dtype::of<float>(), {py::ssize_t(height), py::ssize_t(width), py::ssize_t(channels)},
        {pixel * py::ssize_t(width), pixel, py::ssize_t(sizeof(float))}, owned->data(), owner);
}

} // namespace

py::array rgbArray(std::vector<float>&& rgba, uint32_t width, uint32_t height) {
    return viewOf(std::move(rgba), width, height, 3);
}

py::array rgbaArray(std::vector<float>&& rgba, uint32_t width, uint32_t height) {
    return viewOf(std::move(rgba), width, height, 4);
}

py::array mapArray(const std::vector<double>& map, uint32_t width, uint32_t height) {
    py::array_t<double> out({py::ssize_t(height), py::ssize_t(width)});
    std::copy(map.begin(), map.end(), out.mutable_data());
    return out;
}

metrics::Image imageFrom(const py::handle& object, const std::string& what) {
    py::array_t<float, py::array::c_style | py::array::forcecast> a;
    try {
        a = py::array_t<float, py::array::c_style | py::array::forcecast>::ensure(object);
    } catch (const py::error_already_set&) {
    }
    if (!a || a.ndim() != 3 || (a.shape(2) != 3 && a.shape(2) != 4))
        throw InputError(what + ": expected an image, an array of numbers of shape (height, " +
                         "width, 3) or (height, width, 4)");
    if (a.shape(0) < 1 || a.shape(1) < 1 || a.shape(0) > 65536 || a.shape(1) > 65536)
        throw InputError(what + ": an image must be 1 to 65536 pixels on each side, not " +
                         std::to_string(a.shape(1)) + "x" + std::to_string(a.shape(0)));
    metrics::Image image;
    image.width = uint32_t(a.shape(1));
    image.height = uint32_t(a.shape(0));
    const size_t channels = size_t(a.shape(2));
    image.rgba.assign(image.pixels() * 4, 1.0f);
    const float* in = a.data();
    for (size_t i = 0; i < image.pixels(); ++i)
        for (size_t c = 0; c < channels; ++c)
            image.rgba[4 * i + c] = in[channels * i + c];
    return image;
}

bool isPath(const py::handle& object) {
    return py::isinstance<py::str>(object) || py::hasattr(object, "__fspath__");
}

std::string pathFrom(const py::handle& path) {
    const py::object text = py::module_::import("os").attr("fspath")(path);
    if (!py::isinstance<py::str>(text)) throw InputError("a path must be a str or os.PathLike");
    return text.cast<std::string>();
}

namespace {

// The value as the text a command line would hold, for the programs' own checks.
std::string textOf(const std::string& name, const py::handle& value, bool whole) {
    if (py::isinstance<py::bool_>(value) ||
        !(py::isinstance<py::int_>(value) || (!whole && py::isinstance<py::float_>(value))))
        throw InputError(name + ": expected " + (whole ? "a whole number" : "a number") + ", got " +
                         std::string(py::str(py::type::of(value).attr("__name__"))));
    if (py::isinstance<py::int_>(value)) return std::string(py::str(value));
    char text[40];
    std::snprintf(text, sizeof text, "%.17g", value.cast<double>());
    return text;
}

} // namespace

double numberArg(const std::string& name, const py::handle& value, double lo, double hi) {
    return cli::parseNumber(name, textOf(name, value, false), lo, hi);
}

uint32_t countArg(const std::string& name, const py::handle& value, uint32_t lo, uint32_t hi) {
    const std::string text = textOf(name, value, true);
    char* end = nullptr;
    const long long n = std::strtoll(text.c_str(), &end, 10);
    if (*end != '\0' || n < lo || n > hi)
        throw InputError(name + ": '" + text + "' is not a whole number in " + std::to_string(lo) +
                         ".." + std::to_string(hi));
    return uint32_t(n);
}

void sizeArg(const py::handle& size, uint32_t& width, uint32_t& height, uint32_t lo, uint32_t hi) {
    py::tuple pair;
    try {
        pair = py::tuple(py::reinterpret_borrow<py::object>(size));
    } catch (const py::error_already_set&) {
    }
    if (!pair || pair.size() != 2) throw InputError("size: expected (width, height)");
    width = countArg("size", pair[0], lo, hi);
    height = countArg("size", pair[1], lo, hi);
}

} // namespace ssgi::python
