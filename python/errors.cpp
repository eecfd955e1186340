// The module's exceptions: one tree under ssgi.Error, each class also the Python built-in that
// users catch for its kind of problem, and the one translator from the library's C++ exceptions
// to them. The message is always the programs' error line, refused value included.
#include "module.h"

#include "vk/context.h"

#include <pybind11/eval.h>

#include <cerrno>

namespace ssgi::python {

namespace {

// The classes, made by Python itself (docstrings, and KeyError's str() that would otherwise
// quote the message).
constexpr const char* kClasses = R"(
class Error(Exception):
    """The base class of every error the module raises for its own reasons: catch it to catch
    them all. The message is the programs' error line."""

class InputError(Error, ValueError):
    """Bad input (a ValueError): a scene, a setting, a size, a view, a device that is not there,
    an image, a path; the message is the programs' error line, naming the refused value."""

class FileError(InputError, OSError):
    """An input file that cannot be read: not a regular file, not readable (an OSError, and an
    InputError)."""

class MissingFileError(FileError, FileNotFoundError):
    """An input file that is not there (a FileNotFoundError, and an InputError)."""

class SettingNameError(InputError, KeyError):
    """A setting's name that the settings table lacks (a KeyError, and an InputError); the
    message lists the names it has."""
    def __str__(self):
        """The message, unquoted (KeyError's own str() quotes it)."""
        return Exception.__str__(self)

class ArgumentTypeError(Error, TypeError):
    """An argument of the wrong type (a TypeError): None for a scene, a str for a number."""

class RenderError(Error, RuntimeError):
    """A render that failed (a RuntimeError): the reference's samples not finite, an image read
    back wrong."""

class VulkanError(RenderError):
    """A failure of the Vulkan device (a RuntimeError, and a RenderError)."""
)";

py::dict* classes = nullptr; // the namespace the classes were made in, never destroyed

void raise(const char* name, const std::string& message, int error = 0) {
    const py::object type = (*classes)[name];
    const py::object value = type(message);
    if (error != 0) value.attr("errno") = error;
    PyErr_SetObject(type.ptr(), value.ptr());
}

bool endsWith(const std::string& text, const std::string& end) {
    return text.size() >= end.size() &&
           text.compare(text.size() - end.size(), end.size(), end) == 0;
}

// The library says what is wrong with a file in its message, in the words of readInputFile and
// readImage (renderer/scene/gltf_files.cpp, renderer/image_io.cpp): the class follows them.
void raiseInput(const std::string& message) {
    if (endsWith(message, ": file not found") ||
        endsWith(message, ": cannot read image: No such file or directory"))
        return raise("MissingFileError", message, ENOENT);
    if (endsWith(message, ": not a regular file") ||
        message.find(": cannot read: ") != std::string::npos ||
        message.find(": cannot read image: ") != std::string::npos ||
        endsWith(message, ": cannot open file for reading") || endsWith(message, ": read error"))
        return raise("FileError", message);
    raise("InputError", message);
}

} // namespace

void defineErrors(py::module_& m) {
    classes = new py::dict();
    (*classes)["__name__"] = "ssgi";
    py::exec(kClasses, *classes);
    for (const char* name : {"Error", "InputError", "FileError", "MissingFileError",
                             "SettingNameError", "ArgumentTypeError", "RenderError", "VulkanError"})
        m.attr(name) = (*classes)[name];
    py::register_exception_translator([](std::exception_ptr thrown) {
        try {
            if (thrown) std::rethrow_exception(thrown);
        } catch (const SettingNameError& e) {
            raise("SettingNameError", e.what());
        } catch (const InputError& e) {
            raiseInput(e.what());
        } catch (const ArgumentTypeError& e) {
            raise("ArgumentTypeError", e.what());
        } catch (const vk::VulkanError& e) {
            raise("VulkanError", e.what());
        } catch (const py::builtin_exception&) {
            throw; // pybind11's own (KeyError, StopIteration, ...), translated by pybind11
        } catch (const std::runtime_error& e) {
            raise("RenderError", e.what());
        }
    });
}

} // namespace ssgi::python
