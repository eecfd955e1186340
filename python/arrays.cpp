#include "app/cli.h"
#include "module.h"
#include "scene/scene.h"

#include <cerrno>
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

namespace {

py::object numpy() {
    return py::module_::import("numpy");
}

} // namespace

std::string typeName(const py::handle& value) {
    return py::str(py::type::of(value).attr("__name__"));
}

bool holdsIntegers(const py::handle& object) {
    if (!py::isinstance<py::array>(object)) return false;
    const char kind = py::reinterpret_borrow<py::array>(object).dtype().kind();
    return kind == 'u' || kind == 'i';
}

metrics::Image imageFrom(const py::handle& object, const std::string& what) {
    if (object.is_none() || isPath(object) || py::isinstance<py::bytes>(object))
        throw ArgumentTypeError(what + ": expected an array of numbers, got " + typeName(object));
    // The shape and the type are checked before any conversion: an array too large to copy
    // is refused for its size, not for the memory a copy would take.
    py::array a;
    try {
        a = numpy().attr("asarray")(object);
    } catch (const py::error_already_set&) {
        throw ArgumentTypeError(what + ": expected an array of numbers, got " + typeName(object));
    }
    const std::string shape = py::str(py::tuple(a.attr("shape")));
    const bool grey = a.ndim() == 2 || (a.ndim() == 3 && a.shape(2) == 1);
    if (!(grey || (a.ndim() == 3 && (a.shape(2) == 3 || a.shape(2) == 4))))
        throw InputError(what + ": an image is an array of shape (height, width), (height, " +
                         "width, 1), (height, width, 3) or (height, width, 4), not " + shape);
    constexpr py::ssize_t kMaxSide = 65536;
    if (a.shape(0) < 1 || a.shape(1) < 1)
        throw InputError(what + ": an empty image, of shape " + shape);
    if (a.shape(0) > kMaxSide || a.shape(1) > kMaxSide)
        throw InputError(what + ": an image of " + std::to_string(a.shape(1)) + "x" +
                         std::to_string(a.shape(0)) + " pixels is too large: at most " +
                         std::to_string(kMaxSide) + " pixels on each side");
    const py::dtype type = a.dtype();
    const char kind = type.kind();
    double scale = 1.0;
    if (kind == 'u' && type.itemsize() == 1) {
        scale = 1.0 / 255.0;
    } else if (kind == 'u' && type.itemsize() == 2) {
        scale = 1.0 / 65535.0;
    } else if (kind != 'f') {
        const std::string dtype = py::str(type.attr("name"));
        throw InputError(what + ": an image holds floats, uint8 (0..255) or uint16 (0..65535), " +
                         "not " + dtype +
                         (kind == 'i' || kind == 'u'
                              ? "; convert it with .astype(numpy.uint8) or .astype(numpy.float32)"
                              : ""));
    }
    const auto floats = py::array_t<float, py::array::c_style | py::array::forcecast>::ensure(a);
    if (!floats) throw py::error_already_set();
    metrics::Image image;
    image.width = uint32_t(a.shape(1));
    image.height = uint32_t(a.shape(0));
    const size_t channels = grey ? 1 : size_t(a.shape(2));
    image.rgba.assign(image.pixels() * 4, 1.0f);
    const float* in = floats.data();
    const float s = float(scale); // 1 for floats, which a product by 1 leaves as they are
    for (size_t i = 0; i < image.pixels(); ++i) {
        float* out = &image.rgba[4 * i];
        if (grey) {
            out[0] = out[1] = out[2] = in[i] * s;
            continue;
        }
        for (size_t c = 0; c < channels; ++c)
            out[c] = in[channels * i + c] * s;
    }
    return image;
}

bool isPath(const py::handle& object) {
    return py::isinstance<py::str>(object) || py::hasattr(object, "__fspath__");
}

std::string pathFrom(const py::handle& path, const std::string& what) {
    if (!isPath(path))
        throw ArgumentTypeError(what + ": expected a path (str or os.PathLike), got " +
                                typeName(path));
    const py::object text = py::module_::import("os").attr("fspath")(path);
    if (!py::isinstance<py::str>(text))
        throw ArgumentTypeError(what + ": expected a path as str, got " + typeName(text));
    const std::string file = text.cast<std::string>();
    // The system would read the path only up to the NUL: another file than the one named.
    if (file.find('\0') != std::string::npos)
        throw InputError(what + ": the path " + std::string(py::repr(text)) +
                         " holds a NUL character");
    if (file.empty()) throw InputError(what + ": an empty path");
    return file;
}

py::object plainNumber(const py::handle& given, const std::string& what) {
    py::object value = py::reinterpret_borrow<py::object>(given);
    if (py::isinstance<py::bool_>(value) || py::isinstance<py::int_>(value) ||
        py::isinstance<py::float_>(value))
        return value;
    if (py::isinstance<py::str>(value) || py::isinstance<py::bytes>(value)) return value;
    // NumPy's scalars and 0-d arrays (a 0-d array's item() is its Python number).
    if (py::isinstance<py::array>(value)) {
        if (py::reinterpret_borrow<py::array>(value).ndim() != 0) return value;
        value = value.attr("item")();
        if (py::isinstance<py::int_>(value) || py::isinstance<py::float_>(value) ||
            py::isinstance<py::bool_>(value))
            return value;
    }
    const py::object np = numpy();
    if (py::isinstance(value, np.attr("bool_"))) return py::bool_(PyObject_IsTrue(value.ptr()));
    if (PyIndex_Check(value.ptr())) { // NumPy's integers, and any integer type
        PyObject* index = PyNumber_Index(value.ptr());
        if (!index) throw py::error_already_set();
        return py::reinterpret_steal<py::object>(index);
    }
    const py::object real = py::module_::import("numbers").attr("Real");
    if (py::isinstance(value, real)) {
        PyObject* number = PyNumber_Float(value.ptr());
        if (!number) throw py::error_already_set();
        const py::object f = py::reinterpret_steal<py::object>(number);
        const double d = f.cast<double>();
        // float32 and float16 widen exactly; a long double or a fraction may not.
        if (!std::isnan(d) && !value.equal(f))
            throw InputError(what + ": " + std::string(py::repr(value)) + " (" + typeName(value) +
                             ") is not exactly a 64-bit float");
        return f;
    }
    return value;
}

namespace {

// The value as the text a command line would hold, for the programs' own checks.
std::string textOf(const std::string& name, const py::handle& given, bool whole) {
    const py::object value = plainNumber(given, name);
    if (py::isinstance<py::bool_>(value) ||
        !(py::isinstance<py::int_>(value) || (!whole && py::isinstance<py::float_>(value))))
        throw ArgumentTypeError(name + ": expected " +
                                (whole ? "a whole number (int)" : "a number") + ", got " +
                                std::string(py::repr(given)) + " (" + typeName(given) + ")");
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
    errno = 0;
    const long long n = std::strtoll(text.c_str(), &end, 10);
    if (*end != '\0' || errno == ERANGE || n < lo || n > hi)
        throw InputError(name + ": '" + text + "' is not a whole number in " + std::to_string(lo) +
                         ".." + std::to_string(hi));
    return uint32_t(n);
}

void sizeArg(const py::handle& size, uint32_t& width, uint32_t& height, uint32_t lo, uint32_t hi) {
    // An image (an array of two or more dimensions) gives its own size: NumPy's shape is
    // (height, width), the reverse of size's (width, height), so it is taken from the array, not
    // from a tuple that says nothing of its order.
    if (py::isinstance<py::array>(size) && py::reinterpret_borrow<py::array>(size).ndim() >= 2) {
        const py::tuple shape = size.attr("shape");
        width = countArg("size", shape[1], lo, hi);
        height = countArg("size", shape[0], lo, hi);
        return;
    }
    py::tuple pair;
    if (!py::isinstance<py::str>(size) && !py::isinstance<py::bytes>(size)) {
        try {
            pair = py::tuple(py::reinterpret_borrow<py::object>(size));
        } catch (const py::error_already_set&) {
        }
    }
    if (!pair || pair.size() != 2)
        throw ArgumentTypeError("size: expected (width, height), got " +
                                std::string(py::repr(size)));
    width = countArg("size", pair[0], lo, hi);
    height = countArg("size", pair[1], lo, hi);
}

bool boolArg(const std::string& name, const py::handle& given) {
    const py::object value = plainNumber(given, name);
    if (!py::isinstance<py::bool_>(value))
        throw ArgumentTypeError(name + ": expected True or False, got " +
                                std::string(py::repr(given)) + " (" + typeName(given) + ")");
    return value.cast<bool>();
}

} // namespace ssgi::python
