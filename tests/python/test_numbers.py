"""Every numeric argument and setting takes Python and NumPy numbers (any integer or floating
type, 0-d arrays) as the Python number they equal, or refuses them showing the value."""
import math

import numpy as np
import pytest
import ssgi
from conftest import CORNELL

INTEGERS = [np.int8, np.int16, np.int32, np.int64, np.uint8, np.uint16, np.uint32, np.uint64]
FLOATS = [np.float16, np.float32, np.float64]


@pytest.mark.parametrize("kind", INTEGERS + [lambda v: np.array(v), int])
def test_an_integer_setting_takes_any_integer(kind):
    scene = ssgi.Scene(CORNELL)
    scene.settings["indirect_vpls"] = kind(64)
    assert scene.settings["indirect_vpls"] == 64 and type(scene.settings["indirect_vpls"]) is int
    # A setting whose range holds 0: a NumPy integer read as 0 would pass unseen.
    row = next(r for r in ssgi.settings_table() if r["type"] == "int" and r["min"] <= 0)
    scene.settings[row["name"]] = kind(1)
    assert scene.settings[row["name"]] == 1


@pytest.mark.parametrize("kind", FLOATS + [lambda v: np.array(v, np.float32), float])
def test_a_float_setting_takes_any_float_exactly(kind):
    scene = ssgi.Scene(CORNELL)
    scene.settings["ao_radius"] = kind(0.25)
    assert scene.settings["ao_radius"] == 0.25
    scene.settings["exposure"] = kind(0.1)
    assert scene.settings["exposure"] == float(kind(0.1))  # float32's 0.1, widened exactly


def test_flags_take_numpy_bools_and_settings_given_whole():
    scene = ssgi.Scene(CORNELL, settings={"ao": np.bool_(False), "ao_steps": np.int64(2),
                                          "exposure": np.float32(0.5)})
    assert (scene.settings["ao"], scene.settings["ao_steps"], scene.settings["exposure"]) == (
        False, 2, 0.5)
    scene.settings.update({"ao": np.True_, "cache": np.array(0)})
    assert scene.settings["ao"] is True and scene.settings["cache"] == 0


def test_numbers_that_are_not_what_they_seem_are_refused_with_their_value():
    scene = ssgi.Scene(CORNELL)
    with pytest.raises(ValueError, match=r"setting 'ao_steps' is 2\.5, and must be a whole number"):
        scene.settings["ao_steps"] = np.float64(2.5)
    with pytest.raises(ValueError, match=r"'indirect_vpls' is 0, outside \[1, 1024\]"):
        scene.settings["indirect_vpls"] = np.int64(0)
    with pytest.raises(ValueError, match=r"'indirect_vpls' is 18446744073709551615, outside "
                                         r"\[1, 1024\]"):
        scene.settings["indirect_vpls"] = np.uint64(2**64 - 1)
    with pytest.raises(ValueError, match=r"'exposure' is -100000000000000000001, outside "
                                         r"\[1e-06, 1e\+06\]"):
        scene.settings["exposure"] = -10**20 - 1
    with pytest.raises(ValueError, match=r"'exposure' is 1\.18059e\+21, outside"):
        scene.settings["exposure"] = 2**70  # a double holds it exactly: --set's message
    with pytest.raises(ValueError, match=r"0\.333\d* \(float\d+\) is not exactly a 64-bit"):
        scene.settings["exposure"] = np.longdouble(1) / 3
    with pytest.raises(TypeError, match=r"must be a number or a bool, not '0.5' \(str\)"):
        scene.settings["exposure"] = "0.5"
    with pytest.raises(TypeError, match=r"not \(1\+2j\) \(complex\)"):
        scene.settings["exposure"] = 1 + 2j
    with pytest.raises(TypeError, match=r"not array\(\[1, 2\]\) \(ndarray\)"):
        scene.settings["exposure"] = np.array([1, 2])
    with pytest.raises(ValueError, match=r"'exposure' is nan, outside"):
        scene.settings["exposure"] = np.float32(math.nan)


def test_arguments_take_numpy_numbers():
    scene = ssgi.Scene(CORNELL)
    renderer = ssgi.Renderer(scene, size=(np.int64(24), np.uint16(16)))
    assert renderer.size == (24, 16)
    assert renderer.render(frames=np.int32(2)).shape == (16, 24, 3)
    assert renderer.frames == 2
    renderer.render(frames=np.array(1))
    renderer.set_camera(position=np.array([0, 1, 2.5], np.float32), target=(0, np.float64(1), 0),
                        fov=np.float32(50))
    assert renderer.camera["fov"] == pytest.approx(50)
    assert ssgi.Renderer(scene, size=np.array([8, 8])).size == (8, 8)
    image = ssgi.reference(scene, mode="ao", size=(np.int64(6), np.int64(4)), spp=np.uint8(2),
                           seed=np.int64(3), threads=np.int8(1), cache=np.False_)
    assert image.shape == (4, 6, 3)
    figures = ssgi.compare(image, image, exposure=np.float32(2), max_diff=np.int64(1),
                           maps=np.True_)
    assert figures["relmse"] == 0 and figures["diff_fraction"] == 0
    assert ssgi.tonemap(image, exposure=np.float16(1)).shape == (4, 6, 3)
    with pytest.raises(TypeError, match=r"frames: expected a whole number \(int\), got 2.0"):
        renderer.render(frames=np.float64(2))
    with pytest.raises(ValueError, match=r"size: '-1' is not a whole number in 0..1000000"):
        ssgi.Renderer(scene, size=(np.int64(-1), 8))
    with pytest.raises(ValueError, match=r"spp: '4294967296' is not a whole number"):
        ssgi.reference(scene, spp=np.uint64(2**32))


def test_a_sweep_over_numpy_values_renders_what_python_numbers_render():
    """np.arange and np.linspace give NumPy numbers; the sweep's images are those of the same
    sweep written with Python numbers, bit for bit."""
    def sweep(radii, counts):
        images = []
        for radius, count in zip(radii, counts):
            scene = ssgi.Scene(CORNELL, settings={"ao_radius": radius, "world_vpls": count})
            images.append(ssgi.Renderer(scene, size=(32, 32)).render(frames=2).copy())
        return images
    numpy_sweep = sweep(np.linspace(0.1, 0.4, 3), np.arange(16, 64, 16))
    python_sweep = sweep([0.1, 0.25, 0.4], [16, 32, 48])
    for a, b in zip(numpy_sweep, python_sweep):
        assert np.array_equal(a, b)
    assert not np.array_equal(numpy_sweep[0], numpy_sweep[2])  # the sweep changes the image
