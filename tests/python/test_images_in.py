"""write_image takes what NumPy users hold: uint8 (scaled by 1/255), uint16, float16/32/64, with
1, 3 or 4 channels; it says when a PNG clips, and refuses what it cannot write in its own words."""
import warnings

import numpy as np
import pytest
import ssgi

RNG = np.random.default_rng(7)


def test_uint8_is_scaled_not_clipped(tmp_path):
    image = RNG.integers(0, 256, (6, 5, 3), dtype=np.uint8)
    image[0, 0] = 128
    ssgi.write_image(tmp_path / "a.png", image)
    stored = ssgi.read_image(tmp_path / "a.png")
    assert np.array_equal(np.round(stored * 255).astype(np.uint8), image)  # 128 stays 128
    ssgi.write_image(tmp_path / "a.exr", image)
    assert np.array_equal(ssgi.read_image(tmp_path / "a.exr"),
                          (image / np.float32(255)).astype(np.float16).astype(np.float32))


def test_uint16_and_every_float_width(tmp_path):
    image = RNG.integers(0, 65536, (4, 7, 3), dtype=np.uint16)
    ssgi.write_image(tmp_path / "a.exr", image)
    assert np.allclose(ssgi.read_image(tmp_path / "a.exr"), image / 65535, atol=1e-3)
    values = RNG.random((4, 7, 3))
    for dtype in (np.float16, np.float32, np.float64):
        ssgi.write_image(tmp_path / "f.png", values.astype(dtype), linear=True)
        stored = ssgi.read_image(tmp_path / "f.png")
        assert np.abs(stored - values.astype(dtype)).max() <= 0.5 / 255 + 1e-3, dtype


def test_one_three_and_four_channels(tmp_path):
    grey = RNG.random((5, 6), dtype=np.float32)
    for array in (grey, grey[..., None]):
        ssgi.write_image(tmp_path / "g.exr", array)
        stored = ssgi.read_image(tmp_path / "g.exr")
        assert np.array_equal(stored, np.repeat(grey[..., None], 3, axis=2).astype(
            np.float16).astype(np.float32))
    rgba = RNG.random((5, 6, 4), dtype=np.float32)
    ssgi.write_image(tmp_path / "c.png", rgba, linear=True)
    stored = ssgi.read_image(tmp_path / "c.png", alpha=True)
    assert np.abs(stored - rgba).max() <= 0.5 / 255 + 1e-6
    # A view with strides (the renderer's RGB of RGBA) is read as it is shown.
    ssgi.write_image(tmp_path / "v.exr", rgba[:, ::2, :3])
    assert ssgi.read_image(tmp_path / "v.exr").shape == (5, 3, 3)


def test_a_png_says_when_it_clips(tmp_path):
    image = np.full((4, 4, 3), 0.5, np.float32)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        ssgi.write_image(tmp_path / "in.png", image, linear=True)  # nothing outside [0, 1]
        ssgi.write_image(tmp_path / "hdr.exr", image * 40)  # an EXR holds any value
    image[0, 0] = (2.0, -1.0, 0.5)
    with pytest.warns(ssgi.SsgiWarning, match=r"2 values outside \[0, 1\] are clipped"):
        ssgi.write_image(tmp_path / "out.png", image, linear=True)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        ssgi.write_image(tmp_path / "shown.png", image)  # display-encoded: nothing clips
    assert ssgi.read_image(tmp_path / "out.png")[0, 0].tolist() == [1, 0, np.float32(128 / 255)]
    with warnings.catch_warnings():
        warnings.simplefilter("error", ssgi.SsgiWarning)  # filterable: an error, if asked
        with pytest.raises(ssgi.SsgiWarning):
            ssgi.write_image(tmp_path / "strict.png", image, linear=True)
    assert not (tmp_path / "strict.png").exists()


def test_what_cannot_be_written_is_refused_naming_the_problem(tmp_path):
    good = np.zeros((4, 4, 3), np.float32)
    with pytest.raises(ValueError, match=r"path: the path '.*a\\x00b.png' holds a NUL"):
        ssgi.write_image(str(tmp_path / "a") + "\0b.png", good)
    assert list(tmp_path.iterdir()) == []  # nothing written at the cut name
    huge = np.broadcast_to(np.float32(0), (100000, 100000, 3))  # no memory behind it
    with pytest.raises(ValueError, match=r"100000x100000 pixels is too large: at most 65536"):
        ssgi.write_image(tmp_path / "huge.exr", huge)
    with pytest.raises(ValueError, match=r"not int64; convert it"):
        ssgi.write_image(tmp_path / "i.png", np.zeros((4, 4, 3), np.int64))
    with pytest.raises(ValueError, match=r"not \(4, 4, 2\)"):
        ssgi.write_image(tmp_path / "c.png", np.zeros((4, 4, 2)))
    with pytest.raises(ValueError, match=r"an empty image"):
        ssgi.write_image(tmp_path / "e.png", np.zeros((0, 4, 3)))
    with pytest.raises(TypeError, match=r"image: expected an array of numbers, got NoneType"):
        ssgi.write_image(tmp_path / "n.png", None)
    with pytest.raises(TypeError, match=r"path: expected a path \(str or os.PathLike\), got int"):
        ssgi.write_image(3, good)
    with pytest.raises(ValueError, match=r"uint16 \(0..65535\), not complex128"):
        ssgi.write_image(tmp_path / "z.exr", np.zeros((2, 2, 3), complex))
