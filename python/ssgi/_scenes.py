"""The scenes shipped with ssgi: in the installed package (ssgi/scenes/), else in the source tree
the package was built from."""
import pathlib
from typing import List

from . import _build


def _folder() -> pathlib.Path:
    shipped = pathlib.Path(__file__).resolve().parent / "scenes"
    return shipped if shipped.is_dir() else pathlib.Path(_build.SCENES)


def scene_names() -> List[str]:
    """The names of the scenes shipped with ssgi ('cornell-box', 'sponza', ...), which
    scene_file() takes."""
    return sorted(path.stem for path in _folder().glob("*.json"))


def scene_file(name: str) -> pathlib.Path:
    """The file of the shipped scene `name` (one of scene_names()), an absolute path that
    Scene() loads from any folder: ssgi.Scene(ssgi.scene_file('cornell-box'))."""
    from . import ArgumentTypeError, MissingFileError  # the package's, imported by now
    if not isinstance(name, str):
        raise ArgumentTypeError(f"name: expected a scene's name (str), got {type(name).__name__}")
    names = scene_names()
    if name not in names:
        raise MissingFileError(f"scene_file: no shipped scene named {name!r}; the shipped scenes: "
                               f"{', '.join(names)} (in {_folder()})")
    return _folder() / f"{name}.json"
