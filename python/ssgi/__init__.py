"""The ssgi renderer, its path-traced reference and its error metrics, from Python with NumPy
arrays (docs/python.md): Scene, Renderer, reference(), compare(), tonemap(), read_image() and
write_image(); the shipped scenes by name (scene_names(), scene_file()). Every error the module
raises is an ssgi.Error, and also the Python built-in for its kind: InputError (a ValueError)
with the programs' messages, MissingFileError (a FileNotFoundError), ArgumentTypeError (a
TypeError), VulkanError (a RuntimeError). What the library warns about is an SsgiWarning."""
import importlib as _importlib
import sys as _sys

from ._build import MODULE_SUFFIX as _MODULE_SUFFIX
from ._build import PYTHON as _PYTHON
from ._build import PYTHON_VERSION as _PYTHON_VERSION
from ._build import VERSION as __version__


def _built_for():
    return (f"ssgi {__version__} was built for Python {_PYTHON_VERSION} ({_PYTHON}); this is "
            f"Python {_sys.version_info.major}.{_sys.version_info.minor} ({_sys.executable})")


# The compiled module hands images over as NumPy arrays: without NumPy it would import and then
# fail at the first render.
try:
    import numpy as _numpy  # noqa: F401
except ImportError as _error:
    raise ImportError(
        f"{_built_for()}, which cannot import NumPy ({_error}). Run ssgi with the Python it was "
        f"built for, install NumPy for this one (Debian: python3-numpy; a virtual environment: "
        f"python3 -m venv --system-site-packages), or build ssgi for it (pip install "
        f"--no-build-isolation . with it, or cmake -DPython3_EXECUTABLE=...)") from None

try:
    _importlib.import_module(__name__ + "._ssgi")
except ModuleNotFoundError as _error:
    if _error.name != __name__ + "._ssgi":
        raise
    raise ImportError(
        f"{_built_for()}: its compiled module (_ssgi{_MODULE_SUFFIX}) is not one this Python "
        f"loads. Run ssgi with the Python it was built for, or build it for this one (pip "
        f"install --no-build-isolation . with it, or cmake -DPython3_EXECUTABLE=...)") from None

from ._image import Image
from ._scenes import scene_file, scene_names
from ._ssgi import (ArgumentTypeError, Error, FileError, InputError, MissingFileError,
                    RenderError, Renderer, Scene, SettingNameError, Settings, SsgiWarning,
                    VulkanError, compare, read_image, reference, settings_table, tonemap,
                    validation_messages, view_names, write_image)

__all__ = ["ArgumentTypeError", "Error", "FileError", "Image", "InputError", "MissingFileError",
           "RenderError", "Renderer", "Scene", "SettingNameError", "Settings", "SsgiWarning",
           "VulkanError", "compare", "read_image", "reference", "scene_file", "scene_names",
           "settings_table", "tonemap", "validation_messages", "view_names", "write_image"]
