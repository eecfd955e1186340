"""Bad input from Python: an exception carrying the program's message, never a crash."""
import math

import numpy as np
import pytest
import ssgi
from conftest import CORNELL, ROOT, program_error

BAD_SCENES = sorted((ROOT / "tests" / "scenes").glob("bad-*.json"))


@pytest.mark.parametrize("path", BAD_SCENES, ids=lambda p: p.name)
def test_a_bad_scene_raises_the_programs_message(path):
    with pytest.raises(ssgi.InputError) as error:
        ssgi.Scene(path)
    assert str(error.value) == program_error("render", path)


def test_missing_and_unsupported_files():
    for path in ("no-such-scene.json", "README.md"):
        with pytest.raises(ValueError) as error:
            ssgi.Scene(path)
        assert str(error.value) == program_error("render", path)
    with pytest.raises(TypeError):
        ssgi.Scene(42)


@pytest.mark.parametrize("name, value", [("ao_radius", -1), ("ao_steps", 2.5), ("cache", 2),
                                         ("exposure", math.nan), ("no_such_setting", 1)])
def test_a_bad_setting_raises_sets_message(name, value):
    expected = program_error("render", CORNELL, "--set", f"{name}={value}")
    assert expected.startswith("--set: ")
    expected = "settings: " + expected[len("--set: "):]
    with pytest.raises(ValueError) as given:
        ssgi.Scene(CORNELL, settings={name: value})
    assert str(given.value) == expected
    scene = ssgi.Scene(CORNELL)
    before = scene.settings.to_dict()
    with pytest.raises(ValueError) as assigned:
        scene.settings = {"ao_steps": 3, name: value}  # checked whole before any is applied
    assert str(assigned.value) == expected
    assert scene.settings == before
    with pytest.raises(TypeError, match="'yes' \\(str\\)"):
        scene.settings["ao"] = "yes"
    with pytest.raises(KeyError):
        scene.settings["no_such_setting"]


def test_bad_renderer_arguments_raise_renders_messages():
    scene = ssgi.Scene(CORNELL)
    cases = [({"size": (0, 0)}, ["--size", "0x0"], 2),
             ({"size": (5, 100000)}, ["--size", "5x100000"], 2),
             ({"view": "nope"}, ["--view", "nope"], 2),
             ({"device": "no-such-gpu"}, ["--device", "no-such-gpu"], 1)]
    for kwargs, args, status in cases:
        with pytest.raises(ssgi.InputError) as error:  # a device not there too (a bad value)
            ssgi.Renderer(scene, **kwargs)
        expected = program_error("render", CORNELL, *args, status=status)
        assert str(error.value) == expected.replace("--size", "size"), kwargs
    for size in [(-1, 5), (1, 2, 3), "big", None, (1.5, 2)]:
        with pytest.raises((ValueError, TypeError)):
            ssgi.Renderer(scene, size=size)
    renderer = ssgi.Renderer(scene, (16, 16))
    with pytest.raises(ValueError, match="frames"):
        renderer.render(frames=0)
    with pytest.raises(ValueError, match="frames"):
        renderer.render(frames=-3)
    with pytest.raises(ValueError, match="no frame rendered yet"):
        renderer.read("hdr")
    with pytest.raises(ValueError) as error:
        renderer.render(view="nope")
    assert str(error.value) == program_error("render", CORNELL, "--view", "nope")
    renderer.render()
    with pytest.raises(ValueError, match="no image named 'no-such-image' in this frame; it has: "):
        renderer.read("no-such-image")
    for kwargs in [{"position": (0, 1)}, {"target": (math.inf, 0, 0)}, {"fov": 0},
                   {"fov": 200}, {"position": (0, 0, 3), "target": (0, 0, 3)}, {"up": (0, 0, 0)}]:
        with pytest.raises(ValueError):
            renderer.set_camera(**kwargs)
    for seconds in (-1, math.nan):
        with pytest.raises(ValueError):
            renderer.set_time(seconds)
    with pytest.raises(TypeError, match="time: expected a number, got 'soon'"):
        renderer.set_time("soon")
    assert renderer.render().shape == (16, 16, 3)  # still renders


def test_time_on_a_scene_without_paths():
    still = ROOT / "tests" / "scenes" / "empty-box.json"
    renderer = ssgi.Renderer(ssgi.Scene(still), (16, 16))
    with pytest.raises(ValueError) as error:
        renderer.set_time(1.0)
    assert str(error.value) == program_error("render", still, "--time", "1")


def test_bad_reference_arguments_raise_references_messages():
    scene = ssgi.Scene(CORNELL)
    with pytest.raises(ValueError) as error:
        ssgi.reference(scene, mode="nope")
    assert str(error.value) == program_error("reference", CORNELL, "--mode", "nope").replace(
        "--mode", "mode")
    with pytest.raises(ValueError) as error:
        ssgi.reference(scene, mode="ao", jitter=True, size=(4, 4), spp=1)
    assert str(error.value) == program_error("reference", CORNELL, "--mode", "ao", "--jitter")
    for kwargs in [{"spp": 0}, {"size": (0, 4)}, {"noise": 2}, {"threads": -1}]:
        with pytest.raises(ValueError):
            ssgi.reference(scene, **kwargs)


def test_bad_images_raise(tmp_path):
    good = np.zeros((4, 4, 3), np.float32)
    for bad in [np.zeros((4, 4, 5)), np.zeros((4, 4, 2)), np.zeros((0, 4, 3)), "no-such.exr",
                [[["a", "b", "c"]]], None]:
        with pytest.raises((ValueError, TypeError)):
            ssgi.compare(bad, good)
    with pytest.raises(ValueError, match="differs from"):
        ssgi.compare(np.zeros((4, 5, 3)), good)
    nan = good.copy()
    nan[1, 1, 0] = math.nan
    with pytest.raises(ValueError, match="NaN or infinite"):
        ssgi.compare(good, nan)
    assert ssgi.compare(nan, good)["non_finite_pixels"] == 1
    with pytest.raises(RuntimeError, match="NaN or infinite; no image written"):
        ssgi.write_image(tmp_path / "nan.exr", nan)
    with pytest.raises(ValueError, match="must end in .png or .exr"):
        ssgi.write_image(tmp_path / "a.jpg", good)
    ssgi.write_image(tmp_path / "a.png", good)
    ssgi.write_image(tmp_path / "a.exr", good)
    with pytest.raises(ValueError) as error:
        ssgi.compare(tmp_path / "a.png", tmp_path / "a.exr")
    assert str(error.value) == program_error("compare", tmp_path / "a.png", tmp_path / "a.exr")
    with pytest.raises(ValueError) as error:
        ssgi.read_image(tmp_path / "missing.png")
    with pytest.raises(ValueError):
        ssgi.tonemap(good, exposure=0)
