"""Type stub of the ssgi package: every class, function and signature of its compiled module,
which tests/python/test_docs.py checks against the module."""
import os
from typing import Callable, Iterator, List, Mapping, Optional, Sequence, Tuple, Union

import numpy

__version__: str

class InputError(ValueError):
    """Bad input (a ValueError): a scene file, a setting, a size, a view, an image, a path; the
    message is the programs' error line.
    """

class Renderer:
    """The real-time renderer of a scene at a size, on a Vulkan device (a substring of its name;
    None: SSGI_DEVICE, else the first). It renders the scene as it was when the renderer was
    made, at `size`, in `view`, until changed; close() (or a with block) gives its device memory
    back.
    """
    def __init__(
        self,
        scene: Scene,
        size: Tuple[int, int] = (512, 512),
        device: Optional[str] = None,
        view: str = 'final',
        keep: Sequence[str] = [],
    ) -> None:
        """A renderer of `scene` at `size` (width, height) showing `view` (view_names()); `keep`
        names images of the frame that read() must find whole (an effect's raw output, such as
        'ao'; '*' keeps all).
        """
    def render(self, frames: int = 1, view: Optional[str] = None) -> numpy.ndarray:
        """Renders `frames` frames and returns the last one's linear image (the view's linear
        quantity for a debug view) as float32, height x width x 3. `view` switches the view from
        now on (None: the renderer's). Ctrl-C stops it between frames (KeyboardInterrupt); the
        renderer stays usable.
        """
    def read(self, name: str) -> numpy.ndarray:
        """An image of the last frame by name (one of images(): 'ldr', 'gbuffer.normal', ...) as
        float32 RGBA, height x width x 4.
        """
    def images(self) -> List[str]:
        """The names read() accepts in this renderer's frame."""
    def set_time(self, seconds: float) -> None:
        """Moves the camera along the scene's camera path and its objects along theirs, as render
        --time does.
        """
    def set_camera(
        self,
        position: Optional[Sequence[float]] = None,
        target: Optional[Sequence[float]] = None,
        up: Optional[Sequence[float]] = None,
        fov: Optional[float] = None,
    ) -> None:
        """Places the camera (world coordinates; fov vertical, in degrees); what is not given
        stays.
        """
    @property
    def camera(self) -> dict:
        """The camera as a dict: position, target (a point one unit ahead, as set_camera takes it),
        forward, up and fov (degrees).
        """
    def cut(self) -> None:
        """Starts every cached history afresh at the next frame."""
    def profile(self) -> dict:
        """The last frame's {'passes': {name: ms}, 'sum_ms', 'host_ms'} (docs/profiling.md)."""
    def memory(self) -> dict:
        """What the frame graph holds: 'images' by name in bytes, 'shared_bytes', 'shared_images',
        'held_bytes'.
        """
    def close(self) -> None:
        """Gives the renderer's device memory back; any later call but close() raises ValueError.
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
    """A scene file (.json) or a bare glTF (.gltf, .glb), loaded as the programs load it.
    `settings` (a mapping) overrides method settings as --set does.
    """
    def __init__(
        self,
        path: Union[str, os.PathLike],
        settings: Optional[Mapping[str, Union[bool, int, float]]] = None,
    ) -> None:
        """Loads the scene at `path` (str or os.PathLike) with `settings` overriding the method
        settings, as render --set does; ssgi.InputError with render's message for a file it
        refuses.
        """
    @property
    def settings(self) -> Settings:
        """The method settings (an ssgi.Settings mapping); assigning a dict changes the settings it
        names, every one checked before any is applied.
        """
    @settings.setter
    def settings(self, arg1: Mapping[str, Union[bool, int, float]]) -> None:
        ...
    @property
    def path(self) -> str:
        """The scene's file, as given."""
    @property
    def animated(self) -> bool:
        """Whether the scene has a camera path or object paths (set_time moves along them)."""
    def __repr__(self) -> str:
        """ssgi.Scene(path, settings={...}) with the settings given from Python."""

class Settings:
    """The scene's method settings by name (docs/settings.md), a mapping: read, assign and update()
    like a dict. Each value is of the table's type (bool, int, float); Python and NumPy numbers
    are taken, each checked against the setting's range.
    """
    def __getitem__(self, name: str) -> Union[bool, int, float]:
        """The setting's value; KeyError for a name not in the table."""
    def __setitem__(self, name: str, value: Union[bool, int, float]) -> None:
        """Sets one setting, checked as --set checks it (ValueError out of range)."""
    def __contains__(self, name: object) -> bool:
        """Whether the settings table has this name."""
    def __len__(self) -> int:
        """The number of settings."""
    def __iter__(self) -> Iterator:
        """The settings' names, in the table's order."""
    def keys(self) -> object:
        """The settings' names."""
    def values(self) -> object:
        """The settings' values."""
    def items(self) -> object:
        """The (name, value) pairs."""
    def get(self, name: str, default: object = None) -> object:
        """The setting's value, or `default` for a name not in the table."""
    def update(self, values: Mapping[str, Union[bool, int, float]]) -> None:
        """Sets the settings a mapping names, every value checked before any is applied."""
    def to_dict(self) -> dict:
        """A dict of every setting's current value."""
    def __eq__(self, other: object) -> bool:
        """Whether `other` (a mapping) holds the same values."""
    def __repr__(self) -> str:
        """The settings as a dict's repr."""

class SsgiWarning(UserWarning):
    """What the renderer, the scene loader, the reference cache or the image writer warns about."""

class VulkanError(RuntimeError):
    """A failure of the Vulkan device (a RuntimeError), or a device that is not there."""

def compare(
    a: Union[numpy.ndarray, str, os.PathLike],
    b: Union[numpy.ndarray, str, os.PathLike],
    exposure: float = 1.0,
    ppd: float = 67.0,
    max_diff: Optional[float] = None,
    linear: Optional[bool] = None,
    maps: bool = True,
) -> dict:
    """compare's figures of `a` against the reference `b` (arrays or files): relmse, rmse, mae,
    ssim, flip, pixels, non_finite_pixels, reference_noise and reference_samples (what a
    reference's EXR records of itself, else None), diff_fraction (with max_diff) and the per-pixel
    maps.
    `linear`: whether arrays hold linear radiance (None: float arrays do, uint8/uint16 ones hold
    display values).
    """

def read_image(path: Union[str, os.PathLike], alpha: bool = False) -> numpy.ndarray:
    """An .exr (linear) or .png (display values in [0, 1]) as float32, height x width x 3 (x 4 with
    alpha=True).
    """

def reference(
    scene: Scene,
    *,
    mode: str = 'full',
    size: Tuple[int, int] = (256, 256),
    spp: int = 65536,
    noise: Optional[float] = 0.01,
    seed: int = 1,
    time: Optional[float] = None,
    jitter: bool = False,
    light_radius: Optional[float] = None,
    threads: int = 0,
    cache: bool = True,
    cache_dir: Optional[Union[str, os.PathLike]] = None,
    progress: Union[bool, Callable[[float, int, float], object], None] = None,
) -> numpy.ndarray:
    """The path-traced reference as the reference program renders it (and from the same cache),
    float32, height x width x 3, by default as the program's: until its estimated noise is 1%
    (`noise`; 0 or None: no target), at most `spp` samples per pixel. `progress`: True shows reference's bar on stderr (None: when
    stderr is a terminal); a callable is called at most every 50 ms and after each pass with
    (samples done per pixel, spp, estimated noise). Ctrl-C stops it within about 10 ms
    (KeyboardInterrupt).
    """

def settings_table() -> list:
    """Every method setting as a dict: name, type, default, min, max, group and meaning
    (docs/settings.md).
    """

def tonemap(image: numpy.ndarray, exposure: float = 1.0) -> numpy.ndarray:
    """The composite pass's display transform: times exposure, the ACES fit, sRGB encoding."""

def validation_messages() -> int:
    """Messages the validation layer has reported so far on every device (tests require 0)."""

def view_names() -> List[str]:
    """The views a renderer can show ('final' and the debug views)."""

def write_image(path: Union[str, os.PathLike], image: numpy.ndarray) -> None:
    """Writes an array as render writes its files: .exr linear (half floats where they hold every
    value), .png 8-bit of display values in [0, 1] (outside clipped, with an ssgi.SsgiWarning);
    whole or not at all. The array is (h, w) grey or (h, w, 1, 3 or 4) of floats, uint8 (scaled
    by 1/255) or uint16 (by 1/65535).
    """
