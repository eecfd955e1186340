"""ssgi.Image: what render() and reference() return, a NumPy array (height x width x 3 of linear
float32) that shows itself in a notebook and carries what a reference records of itself."""
from __future__ import annotations

import os
import tempfile
from typing import Optional

import numpy


class Image(numpy.ndarray):
    """A NumPy array of an image (height x width x channels) that a notebook shows (_repr_png_:
    display-encoded as render's PNG is) and that carries, for a reference, its `samples` per
    pixel and its estimated `noise` (None where unknown), which compare() reads as it reads a
    reference's EXR. Any NumPy operation takes it as the array it is."""

    samples: Optional[int]
    noise: Optional[float]

    def __new__(cls, array: numpy.ndarray, noise: Optional[float] = None,
                samples: Optional[int] = None) -> Image:
        """`array` as an Image (a view, no copy) carrying `noise` and `samples`."""
        image = numpy.asarray(array).view(cls)
        image.noise = noise
        image.samples = samples
        return image

    def __array_finalize__(self, obj: object) -> None:
        """A view or a result of an Image carries what it carried."""
        self.noise = getattr(obj, "noise", None)
        self.samples = getattr(obj, "samples", None)

    def __reduce__(self) -> tuple:
        """Pickled with what it carries (ndarray's own pickling would drop it)."""
        return (Image, (numpy.asarray(self), self.noise, self.samples))

    def _repr_png_(self) -> Optional[bytes]:
        """The image as a PNG, display-encoded (a notebook shows it); None for an array that is
        not an image."""
        from . import write_image  # the package's (and its stub's), imported by now
        array = numpy.asarray(self)
        if array.ndim not in (2, 3) or min(array.shape[:2]) < 1:
            return None
        with tempfile.TemporaryDirectory() as folder:
            path = os.path.join(folder, "image.png")
            write_image(path, array)
            with open(path, "rb") as file:
                return file.read()
