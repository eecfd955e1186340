"""Type stub of the ssgi package: every class, function and signature of its compiled module
and of its Python files, which tests/python/test_docs.py checks against the module (and
test_typing.py with mypy and stubtest). Numbers are as wide as the module takes them: NumPy's
integers, floats and bools too."""
import os
import pathlib
from typing import (Any, Callable, ItemsView, Iterator, KeysView, List, Mapping, Optional,
                    Sequence, Tuple, Union, ValuesView)

import numpy

__version__: str

class Error(Exception):
    """The base class of every error the module raises for its own reasons: catch it to catch
    them all. The message is the programs' error line.
    """

class InputError(Error, ValueError):
    """Bad input (a ValueError): a scene, a setting, a size, a view, a device that is not there,
    an image, a path; the message is the programs' error line, naming the refused value.
    """

class FileError(InputError, OSError):
    """An input file that cannot be read: not a regular file, not readable (an OSError, and an
    InputError).
    """

class MissingFileError(FileError, FileNotFoundError):
    """An input file that is not there (a FileNotFoundError, and an InputError)."""

class SettingNameError(InputError, KeyError):
    """A setting's name that the settings table lacks (a KeyError, and an InputError); the
    message lists the names it has.
    """

class ArgumentTypeError(Error, TypeError):
    """An argument of the wrong type (a TypeError): None for a scene, a str for a number."""

class RenderError(Error, RuntimeError):
    """A render that failed (a RuntimeError): the reference's samples not finite, an image read
    back wrong.
    """

class VulkanError(RenderError):
    """A failure of the Vulkan device (a RuntimeError, and a RenderError)."""

class SsgiWarning(UserWarning):
    """What the renderer, the scene loader, the reference cache or the image writer warns about.
    """

class Image(numpy.ndarray):
    """A NumPy array of an image (height x width x channels) that a notebook shows (_repr_png_:
    display-encoded as render's PNG is) and that carries, for a reference, its `samples` per
    pixel and its estimated `noise` (None where unknown), which compare() reads as it reads a
    reference's EXR. Any NumPy operation takes it as the array it is.
    """
    samples: Optional[int]
    noise: Optional[float]
    def __new__(
        cls,
        array: numpy.ndarray,
        noise: Optional[float] = None,
        samples: Optional[int] = None,
    ) -> Image: ...
    def __array_finalize__(self, obj: object) -> None: ...
    def __reduce__(self) -> tuple: ...
    def _repr_png_(self) -> Optional[bytes]:
        """The image as a PNG, display-encoded (a notebook shows it); None for an array that is
        not an image."""

def scene_names() -> List[str]:
    """The names of the scenes shipped with ssgi ('cornell-box', 'sponza', ...), which
    scene_file() takes."""

def scene_file(name: str) -> pathlib.Path:
    """The file of the shipped scene `name` (one of scene_names()), an absolute path that Scene()
    loads from any folder: ssgi.Scene(ssgi.scene_file('cornell-box'))."""

class Renderer:
    """The real-time renderer of a scene at a size, on a Vulkan device (a substring of its name;
    None: SSGI_DEVICE, else the first). A change of the scene's settings (here or through the
    scene) applies at the next render(), restarting every cache; set_camera, set_light and
    set_time apply at the next frame, restarting what they invalidate. close() (or a with block)
    gives its device memory back.
    """
    def __init__(
        self,
        scene: Scene,
        size: Union[Tuple[Union[int, numpy.integer], Union[int, numpy.integer]], numpy.ndarray] = (512, 512),
        device: Optional[str] = None,
        view: str = 'final',
        keep: Sequence[str] = [],
    ) -> None:
        """A renderer of `scene` at `size` (width, height: NumPy's shape is (height, width))
        showing `view` (view_names()); `keep` names images of the frame that read() must find
        whole (an effect's raw output, such as 'ao'; '*' keeps all).
        """
    def render(self, frames: Union[int, numpy.integer] = 1, view: Optional[str] = None) -> Image:
        """Renders `frames` frames and returns the last one's linear image (the view's linear
        quantity for a debug view) as an ssgi.Image of float32, height x width x 3. A change of
        the scene's settings since the last frame rebuilds the renderer first (its frames are
        then those of a new Renderer). `view` switches the view from now on (None: the
        renderer's). Ctrl-C stops it between frames (KeyboardInterrupt); the renderer stays
        usable.
        """
    def read(self, name: str) -> numpy.ndarray:
        """An image of the last frame by name (one of images(): 'ldr', 'gbuffer.normal', ...) as
        float32 RGBA, height x width x 4; an image of integers (the world cache's keys, lists
        and voxels) as its integers, uint32 or uint8, height x width.
        """
    def images(self) -> List[str]:
        """The names read() accepts in this renderer's frame."""
    def set_time(self, seconds: Union[float, numpy.floating, numpy.integer]) -> None:
        """Moves the camera along the scene's camera path and its objects along theirs, as render
        --time does.
        """
    def set_camera(
        self,
        position: Optional[Union[Sequence[Union[float, numpy.floating, numpy.integer]], numpy.ndarray]] = None,
        target: Optional[Union[Sequence[Union[float, numpy.floating, numpy.integer]], numpy.ndarray]] = None,
        up: Optional[Union[Sequence[Union[float, numpy.floating, numpy.integer]], numpy.ndarray]] = None,
        fov: Optional[Union[float, numpy.floating, numpy.integer]] = None,
    ) -> None:
        """Places the camera (world coordinates; fov vertical, in degrees); what is not given
        stays: a new position alone keeps looking at the camera's target.
        """
    @property
    def camera(self) -> dict:
        """The camera as a dict: position, target (the point it looks at: the target set last, else
        the point of its view nearest the scene's centre), forward, up and fov (degrees).
        """
    def set_light(
        self,
        position: Optional[Union[Sequence[Union[float, numpy.floating, numpy.integer]], numpy.ndarray]] = None,
        direction: Optional[Union[Sequence[Union[float, numpy.floating, numpy.integer]], numpy.ndarray]] = None,
        target: Optional[Union[Sequence[Union[float, numpy.floating, numpy.integer]], numpy.ndarray]] = None,
        color: Optional[Union[Sequence[Union[float, numpy.floating, numpy.integer]], numpy.ndarray]] = None,
        intensity: Optional[Union[float, numpy.floating, numpy.integer]] = None,
        cone: Optional[Union[float, numpy.floating, numpy.integer]] = None,
        inner_cone: Optional[Union[float, numpy.floating, numpy.integer]] = None,
        radius: Optional[Union[float, numpy.floating, numpy.integer]] = None,
    ) -> None:
        """Changes the spot light from the next frame on, checked as a scene file's 'light' is
        (cone angles in degrees); what is not given stays. The caches that depend on the light
        start over.
        """
    @property
    def light(self) -> dict:
        """The light as a dict: position, direction, color, intensity, cone, inner_cone (degrees)
        and radius.
        """
    @property
    def settings(self) -> Settings:
        """The settings of the renderer's scene (its scene.settings): a change applies at the next
        render(), which rebuilds the renderer from the changed scene.
        """
    @settings.setter
    def settings(
        self,
        arg1: Mapping[str, Union[bool, int, float, numpy.bool_, numpy.integer, numpy.floating]],
    ) -> None: ...
    @property
    def scene(self) -> Scene:
        """The scene the renderer renders."""
    def cut(self) -> None:
        """Starts every cached history afresh at the next frame."""
    def profile(self) -> dict:
        """The last frame's {'passes': {name: ms}, 'invocations': {name: compute invocations
        dispatched}, 'sum_ms', 'host_ms'} (docs/profiling.md)."""
    def memory(self) -> dict:
        """What the frame graph holds: 'images' by name in bytes, 'shared_bytes', 'shared_images',
        'held_bytes'.
        """
    def close(self) -> None:
        """Gives the renderer's device memory back; any later call but close() raises
        ssgi.InputError (a ValueError).
        """
    def __enter__(self) -> Renderer:
        """The renderer itself."""
    def __exit__(self, type: object, value: object, traceback: object) -> bool:
        """Closes the renderer."""
    def __repr__(self) -> str:
        """The scene, the size, the view and the device."""
    @property
    def size(self) -> tuple:
        """(width, height) of the images."""
    @property
    def view(self) -> str:
        """The view render() shows."""
    @property
    def cuts(self) -> int:
        """Cuts so far, requested or automatic."""
    @property
    def rebuilds(self) -> int:
        """Times a change of the scene rebuilt the renderer."""
    @property
    def frames(self) -> int:
        """Frames rendered so far (read from another thread too)."""
    @property
    def closed(self) -> bool:
        """Whether close() was called."""
    @property
    def device(self) -> str:
        """The device's name and driver."""
    @property
    def validation(self) -> bool:
        """Whether the validation layer is on."""

class Scene:
    """A scene file (.json) or a bare glTF (.gltf, .glb), loaded as the programs load it, or a dict
    of the scene file's schema (from_dict). `settings` (a mapping) overrides method settings as
    --set does. The shipped scenes: ssgi.scene_names(), ssgi.scene_file(). A scene pickles (and
    copies) as what it was loaded from and the settings Python set.
    """
    def __init__(
        self,
        path: Union[str, os.PathLike],
        settings: Optional[Mapping[str, Union[bool, int, float, numpy.bool_, numpy.integer, numpy.floating]]] = None,
    ) -> None:
        """Loads the scene at `path` (str or os.PathLike) with `settings` overriding the method
        settings, as render --set does; ssgi.InputError with render's message for a file it
        refuses (ssgi.MissingFileError, a FileNotFoundError, for one not there).
        """
    @staticmethod
    def from_dict(
        scene: dict,
        base: Optional[Union[str, os.PathLike]] = None,
        settings: Optional[Mapping[str, Union[bool, int, float, numpy.bool_, numpy.integer, numpy.floating]]] = None,
    ) -> Scene:
        """A scene from a dict of the scene file's schema (docs/scene-format.md), checked as a file
        is (messages name it '<dict>'); its glTF paths are relative to `base` (None: the working
        folder).
        """
    @property
    def settings(self) -> Settings:
        """The method settings (an ssgi.Settings mapping); assigning a dict changes the settings it
        names, every one checked before any is applied.
        """
    @settings.setter
    def settings(
        self,
        arg1: Mapping[str, Union[bool, int, float, numpy.bool_, numpy.integer, numpy.floating]],
    ) -> None: ...
    @property
    def path(self) -> str:
        """The scene's file, as given ('<dict>' for a scene from a dict)."""
    @property
    def animated(self) -> bool:
        """Whether the scene has a camera path or object paths (set_time moves along them)."""
    def __copy__(self) -> Scene:
        """A scene of its own (a change of either leaves the other as it is)."""
    def __deepcopy__(self, memo: object) -> Scene:
        """As __copy__: the loaded scene is shared until either changes."""
    def __getstate__(self) -> tuple:
        ...
    def __setstate__(self, arg0: tuple) -> None:
        ...
    def __repr__(self) -> str:
        """ssgi.Scene(path, settings={...}) with the settings given from Python."""

class Settings:
    """The scene's method settings by name (docs/settings.md), a collections.abc.MutableMapping:
    read, assign, update() and del like a dict's. Each value is of the table's type (bool, int,
    float); Python and NumPy numbers are taken, each checked against the setting's range. A name
    the table lacks is an ssgi.SettingNameError (a KeyError). del forgets what Python set: the
    setting is the scene file's again.
    """
    def __getitem__(self, name: str) -> Union[bool, int, float]:
        """The setting's value; ssgi.SettingNameError (a KeyError) for a name not in the table.
        """
    def __setitem__(
        self,
        name: str,
        value: Union[bool, int, float, numpy.bool_, numpy.integer, numpy.floating],
    ) -> None:
        """Sets one setting, checked as --set checks it (ssgi.InputError out of range)."""
    def __delitem__(self, name: str) -> None:
        """Forgets what Python set of the setting: the scene file's value."""
    def __contains__(self, name: object) -> bool:
        """Whether the settings table has this name."""
    def __len__(self) -> int:
        """The number of settings."""
    def __iter__(self) -> Iterator[str]:
        """The settings' names, in the table's order."""
    def keys(self) -> KeysView[str]:
        """The settings' names."""
    def values(self) -> ValuesView[Union[bool, int, float]]:
        """The settings' values."""
    def items(self) -> ItemsView[str, Union[bool, int, float]]:
        """The (name, value) pairs."""
    def get(self, name: str, default: object = None) -> Any:
        """The setting's value, or `default` for a name not in the table."""
    def pop(self, name: str, default: object = None) -> Union[bool, int, float]:
        """The setting's value, forgetting what Python set of it (as del)."""
    def popitem(self) -> tuple:
        """Forgets one setting set from Python and returns it with the value it had; KeyError when
        none was.
        """
    def clear(self) -> None:
        """Forgets every setting set from Python: the scene file's values."""
    def setdefault(self, name: str, default: object = None) -> Union[bool, int, float]:
        """The setting's value (every setting has one)."""
    def update(self, values: object = None, **kwargs) -> None:
        """Sets the settings a mapping (or (name, value) pairs, or keywords) names, every value
        checked before any is applied.
        """
    def to_dict(self) -> dict:
        """A dict of every setting's current value."""
    def __eq__(self, other: object) -> bool:
        """Whether `other` (a mapping) holds the same values."""
    def __repr__(self) -> str:
        """The settings as a dict's repr."""

def compare(
    a: Union[numpy.ndarray, str, os.PathLike],
    b: Union[numpy.ndarray, str, os.PathLike],
    exposure: Union[float, numpy.floating, numpy.integer] = 1.0,
    ppd: Union[float, numpy.floating, numpy.integer] = 67.0,
    max_diff: Optional[Union[float, numpy.floating, numpy.integer]] = None,
    linear: Optional[Union[bool, numpy.bool_]] = None,
    maps: Union[bool, numpy.bool_] = True,
) -> dict:
    """compare's figures of `a` against the reference `b` (arrays or files): relmse, rmse, mae,
    ssim, flip, pixels, non_finite_pixels, reference_noise and reference_samples (what a
    reference's EXR records of itself, else None), diff_fraction (with max_diff) and the per-
    pixel maps. `linear`: whether arrays hold linear radiance (None: float arrays do,
    uint8/uint16 ones hold display values).
    """

def read_image(
    path: Union[str, os.PathLike],
    alpha: Union[bool, numpy.bool_] = False,
) -> numpy.ndarray:
    """An .exr (linear) or .png (display values in [0, 1]) as float32, height x width x 3 (x 4 with
    alpha=True).
    """

def reference(
    scene: Scene,
    size: Union[Tuple[Union[int, numpy.integer], Union[int, numpy.integer]], numpy.ndarray] = (256, 256),
    *,
    mode: str = 'full',
    spp: Union[int, numpy.integer] = 65536,
    noise: Optional[Union[float, numpy.floating, numpy.integer]] = 0.01,
    seed: Union[int, numpy.integer] = 1,
    time: Optional[Union[float, numpy.floating, numpy.integer]] = None,
    jitter: Union[bool, numpy.bool_] = False,
    light_radius: Optional[Union[float, numpy.floating, numpy.integer]] = None,
    threads: Union[int, numpy.integer] = 0,
    cache: Union[bool, numpy.bool_] = True,
    cache_dir: Optional[Union[str, os.PathLike]] = None,
    progress: Union[bool, Callable[[float, int, float], object], None] = None,
) -> Image:
    """The path-traced reference of `scene` at `size` (width, height) as the reference program
    renders it (and from the same cache): an ssgi.Image of float32, height x width x 3, carrying
    its `samples` per pixel and estimated `noise` (which compare() reads from it as from the
    program's EXR), by default as the program's: until its estimated noise is 1% (`noise`; 0 or
    None: no target), at most `spp` samples per pixel. `progress`: True shows reference's bar on
    stderr (None: when stderr is a terminal); a callable is called at most every 50 ms and after
    each pass with (samples done per pixel, spp, estimated noise). Ctrl-C stops it within about
    10 ms (KeyboardInterrupt).
    """

def settings_table() -> list:
    """Every method setting as a dict: name, type, default, min, max, group and meaning
    (docs/settings.md).
    """

def tonemap(
    image: numpy.ndarray,
    exposure: Union[float, numpy.floating, numpy.integer] = 1.0,
) -> numpy.ndarray:
    """The composite pass's display transform: times exposure, the ACES fit, sRGB encoding;
    negative values (no radiance) display as black, NaN stays NaN.
    """

def validation_messages() -> int:
    """Messages the validation layer has reported so far on every device (tests require 0)."""

def view_names() -> List[str]:
    """The views a renderer can show ('final' and the debug views)."""

def write_image(
    path: Union[str, os.PathLike],
    image: numpy.ndarray,
    linear: Union[bool, numpy.bool_] = False,
    exposure: Union[float, numpy.floating, numpy.integer] = 1.0,
) -> None:
    """Writes an array as render writes its files: .exr linear (half floats where they hold every
    value); .png 8-bit, a float image display-encoded as render's PNG is (tonemap(image,
    exposure)) unless `linear` writes its values as they are (clipped to [0, 1], with an
    ssgi.SsgiWarning); whole or not at all. The array is (h, w) grey or (h, w, 1, 3 or 4) of
    floats, uint8 (scaled by 1/255: display values) or uint16 (by 1/65535).
    """
