"""A session of work as a Python user has it: a scene changed and rendered again on one Renderer,
scenes without files, the shipped scenes from anywhere, one exception tree, the settings as a
MutableMapping, copies and pickles, images that carry what they are."""
import collections.abc
import copy
import json
import os
import pickle
import subprocess
import sys
import time

import numpy as np
import pytest
import ssgi
from conftest import CORNELL, ROOT

SIZE = (24, 16)


def fresh(settings, frames=2, size=SIZE, **calls):
    """The image of a Renderer made anew for `settings`."""
    with ssgi.Renderer(ssgi.Scene(CORNELL, settings), size) as renderer:
        for name, args in calls.items():
            getattr(renderer, name)(**args)
        return renderer.render(frames=frames)


# 1. A live renderer.

@pytest.mark.parametrize("name, values", [("indirect", [False, True]),
                                          ("indirect_vpls", [16, 64, 16]),
                                          ("ao_radius", [0.05, 0.2]),
                                          ("shadow_map_size", [256, 1024])])
def test_a_sweep_on_one_renderer_is_a_new_renderer_per_value(name, values):
    scene = ssgi.Scene(CORNELL)
    with ssgi.Renderer(scene, SIZE) as renderer:
        renderer.render(frames=2)
        for value in values:
            renderer.settings[name] = value  # through the renderer ...
            image = renderer.render(frames=2)
            assert np.array_equal(image, fresh({name: value})), (name, value)
        scene.settings[name] = values[0]  # ... or through its scene
        assert renderer.settings[name] == values[0]
        assert np.array_equal(renderer.render(frames=2), fresh({name: values[0]}))
        assert renderer.rebuilds == len(values) + 1


def other_value(row):
    """A value of the setting other than its default, within its range (and lavapipe's limits:
    a 512-voxel grid's image is wider than it allows)."""
    if row["name"] == "world_voxels":
        return 128
    default, lo, hi = row["default"], row["min"], row["max"]
    if row["type"] == "bool":
        return not default
    if row["type"] == "int":
        value = default * 2 if 0 < default * 2 <= hi else default + 1
        return int(value if value <= hi else default - 1)
    value = default * 1.5 if default != 0 else (0.3 * hi if hi <= 2 else 0.05)
    return float(min(max(value, lo), hi))


def test_every_setting_changed_on_one_renderer_is_a_renderer_made_anew():
    """Each setting changed on a renderer that rendered: the renderer made from the old one's
    parts (its pipelines, its scene on the device, the images drawn once that the change leaves
    as they are) renders what a Renderer made anew renders, bit for bit. The Cornell box under a
    sky (for the sky maps) with a block that moves (set_time)."""
    with open(CORNELL) as f:
        data = json.load(f)
    data["sky"] = {"zenith": [0.1, 0.2, 0.8], "horizon": [0.9, 0.45, 0.1], "ground": [0, 0, 0]}
    data["object_paths"] = [{"object": "short block",
                             "keys": [{"time": 0}, {"time": 1, "translation": [0.05, 0, 0]}]}]

    def anew(name, value, time):
        renderer = ssgi.Renderer(ssgi.Scene.from_dict(data, settings={name: value}), SIZE)
        with renderer:
            if time is not None:
                renderer.set_time(time)
            return renderer.render(frames=2)

    differ = []
    for time in (None, 0.5):
        with ssgi.Renderer(ssgi.Scene.from_dict(data), SIZE) as renderer:
            if time is not None:
                renderer.set_time(time)
            renderer.render()
            for row in ssgi.settings_table():
                name, value = row["name"], other_value(row)
                if time is not None and row["group"] not in ("Shadow", "World cache"):
                    continue  # the second round: the settings of what the objects' move redraws
                renderer.settings[name] = value
                if not np.array_equal(renderer.render(frames=2), anew(name, value, time)):
                    differ.append((name, value, time))
                del renderer.settings[name]
                renderer.render()
    assert differ == []


def test_a_change_is_not_ignored():
    scene = ssgi.Scene(CORNELL)
    renderer = ssgi.Renderer(scene, SIZE)
    before = renderer.render()
    scene.settings["indirect"] = False
    after = renderer.render()
    assert not np.array_equal(before, after)
    assert after.mean() < before.mean()  # the bounce is gone


def test_the_camera_light_time_and_view_carry_over_a_rebuild():
    calls = {"set_camera": {"position": (0.3, 0.3, -0.6)},
             "set_light": {"intensity": 3.0, "cone": 50}}
    renderer = ssgi.Renderer(ssgi.Scene(CORNELL), SIZE)
    for name, args in calls.items():
        getattr(renderer, name)(**args)
    renderer.render()
    renderer.settings["indirect_vpls"] = 16
    assert np.array_equal(renderer.render(frames=2), fresh({"indirect_vpls": 16}, **calls))
    assert renderer.light["intensity"] == 3.0 and abs(renderer.light["cone"] - 50) < 1e-4


def test_the_light_changes_between_frames():
    renderer = ssgi.Renderer(ssgi.Scene(CORNELL), SIZE)
    lit = renderer.render(frames=2)
    renderer.set_light(intensity=0.0)
    assert renderer.render().max() < 0.01 * lit.max()  # restarted: no light left in the caches
    with pytest.raises(ssgi.InputError, match=r"inner_cone: .* less than the cone"):
        renderer.set_light(cone=10, inner_cone=20)
    with pytest.raises(ssgi.InputError, match=r"intensity: '-1' is not a number in"):
        renderer.set_light(intensity=-1)
    with pytest.raises(ssgi.InputError, match="direction"):
        renderer.set_light(direction=(0, 0, 0))


def test_a_change_the_renderer_cannot_take_is_refused_saying_what_to_do():
    scene = ssgi.Scene(CORNELL)
    renderer = ssgi.Renderer(scene, (16200, 2))  # a guard band of 100 makes it 16400 wide
    image = renderer.render()
    scene.settings["guard_band"] = 100
    with pytest.raises(ssgi.InputError, match=r"outside 1\.\.\d+ .*set them back"):
        renderer.render()
    del scene.settings["guard_band"]
    assert np.array_equal(renderer.render(), image)  # a renderer made anew: the same frame


def test_a_change_refused_after_the_old_renderer_gave_its_parts_leaves_one_that_renders():
    """A setting refused while the frame is built (a voxel grid wider than lavapipe's largest
    image), after the old renderer gave the new one its parts: the error says what to do, a
    renderer made anew takes the old one's place, and setting it back renders a new renderer's
    frames."""
    scene = ssgi.Scene(CORNELL)
    with ssgi.Renderer(scene, SIZE) as renderer:
        renderer.render()
        renderer.settings["world_voxels"] = 512
        try:
            renderer.render()  # a device whose images are 32768 wide takes it
        except ssgi.InputError as error:
            assert "world_voxels 512 needs a 32768x128 image" in str(error)
            assert "set them back" in str(error)
        del renderer.settings["world_voxels"]
        assert np.array_equal(renderer.render(frames=2), fresh({}))


def test_a_six_value_sweep_at_96_on_one_renderer_is_a_renderer_per_value():
    """The issue's sweep: six values at 96x96, one Renderer against one per value, the same
    images; its times are printed (with the validation layer on, as every test here runs).
    bench/python_sweep.py measures them: docs/python.md ("What a change costs")."""
    values = [8, 16, 32, 64, 128, 256]
    start = time.perf_counter()
    per_value = [fresh({"indirect_vpls": v}, frames=1, size=(96, 96)) for v in values]
    apart = time.perf_counter() - start
    start = time.perf_counter()
    with ssgi.Renderer(ssgi.Scene(CORNELL), (96, 96)) as renderer:
        swept = []
        for v in values:
            renderer.settings["indirect_vpls"] = v
            swept.append(renderer.render())
    together = time.perf_counter() - start
    for a, b in zip(per_value, swept):
        assert np.array_equal(a, b)
    print(f"sweep of 6 at 96x96: {apart:.2f} s a Renderer per value, {together:.2f} s one")


# 2. One exception tree.

def test_every_error_is_an_ssgi_error_and_pythons_own(tmp_path):
    assert issubclass(ssgi.InputError, ssgi.Error) and issubclass(ssgi.InputError, ValueError)
    assert issubclass(ssgi.MissingFileError, FileNotFoundError)
    assert issubclass(ssgi.MissingFileError, ssgi.InputError)
    assert issubclass(ssgi.FileError, OSError)
    assert issubclass(ssgi.ArgumentTypeError, TypeError)
    assert issubclass(ssgi.ArgumentTypeError, ssgi.Error)
    assert issubclass(ssgi.VulkanError, RuntimeError) and issubclass(ssgi.VulkanError, ssgi.Error)
    assert issubclass(ssgi.SettingNameError, KeyError)
    with pytest.raises(FileNotFoundError) as missing:
        ssgi.Scene(tmp_path / "none.json")
    assert isinstance(missing.value, ssgi.Error) and missing.value.errno == 2
    assert str(missing.value) == f"{tmp_path / 'none.json'}: file not found"
    with pytest.raises(FileNotFoundError):
        ssgi.read_image(tmp_path / "none.exr")
    with pytest.raises(FileNotFoundError):
        ssgi.compare(tmp_path / "none.exr", tmp_path / "none.exr")
    (tmp_path / "folder.json").mkdir()
    with pytest.raises(OSError, match="not a regular file"):
        ssgi.Scene(tmp_path / "folder.json")
    with pytest.raises(ssgi.ArgumentTypeError):
        ssgi.Scene(None)
    with pytest.raises(ssgi.ArgumentTypeError):
        ssgi.Renderer(ssgi.Scene(CORNELL), size="big")


def test_a_device_that_is_not_there_is_input_error():
    with pytest.raises(ssgi.InputError, match="no usable Vulkan device named 'nosuchgpu'"):
        ssgi.Renderer(ssgi.Scene(CORNELL), SIZE, device="nosuchgpu")


def test_every_refused_value_is_in_the_message():
    scene = ssgi.Scene(CORNELL)
    with pytest.raises(ssgi.InputError, match=r"indirect_vpls' is 217\.6, and must be a whole"):
        scene.settings["indirect_vpls"] = 217.6
    with pytest.raises(ssgi.SettingNameError) as unknown:
        scene.settings["no_such"] = 1
    assert "'no_such'" in str(unknown.value) and not str(unknown.value).startswith('"')
    with pytest.raises(KeyError):
        scene.settings["no_such"]
    with pytest.raises(TypeError, match=r"'yes' \(str\)"):
        scene.settings["ao"] = "yes"
    with pytest.raises(TypeError, match=r"3 \(int\)"):
        scene.settings.update({3: 1})


# 3. Scenes without files, and the shipped ones from anywhere.

def test_a_scene_from_a_dict_is_the_files():
    document = json.loads(open(CORNELL).read())
    from_dict = ssgi.Scene.from_dict(document)
    assert from_dict.path == "<dict>"
    a = ssgi.Renderer(from_dict, SIZE).render(frames=2)
    assert np.array_equal(a, fresh({}))
    document["light"]["intensity"] = -1
    with pytest.raises(ssgi.InputError, match=r"^<dict>: .*intensity"):
        ssgi.Scene.from_dict(document)
    with pytest.raises(TypeError):
        ssgi.Scene.from_dict({"objects": {1, 2}})
    bunny = {"gltf": "models/bunny.glb"}
    assert ssgi.Scene.from_dict(bunny, base=ROOT / "scenes").path == "<dict>"


def test_the_shipped_scenes_load_from_any_folder(tmp_path):
    names = ssgi.scene_names()
    assert "cornell-box" in names and "sponza" in names
    assert ssgi.scene_file("cornell-box").is_absolute()
    with pytest.raises(ssgi.MissingFileError, match="no shipped scene named 'nope'.*cornell-box"):
        ssgi.scene_file("nope")
    run = subprocess.run([sys.executable, "-c", "import ssgi; ssgi.Scene(ssgi.scene_file("
                          "'cornell-box'))"], cwd=tmp_path, capture_output=True, text=True)
    assert run.returncode == 0, run.stderr


def test_a_scene_pickles_and_copies():
    scene = ssgi.Scene(CORNELL, {"indirect_vpls": 16})
    for other in (pickle.loads(pickle.dumps(scene)), copy.copy(scene), copy.deepcopy(scene)):
        assert other.settings == scene.settings and other.path == scene.path
        other.settings["indirect_vpls"] = 32
        assert scene.settings["indirect_vpls"] == 16
    from_dict = ssgi.Scene.from_dict(json.loads(open(CORNELL).read()))
    assert pickle.loads(pickle.dumps(from_dict)).settings == from_dict.settings


# 5. The smaller items.

def test_set_camera_keeps_the_target_when_only_the_position_is_given():
    renderer = ssgi.Renderer(ssgi.Scene(CORNELL), SIZE)
    renderer.set_camera(target=(0.278, 0.273, 0.28))
    renderer.set_camera(position=(0.5, 0.3, -0.5))
    camera = renderer.camera
    towards = np.subtract((0.278, 0.273, 0.28), camera["position"])
    assert np.allclose(camera["forward"], towards / np.linalg.norm(towards), atol=1e-5)


def test_an_image_gives_its_size_without_transposing_it():
    image = np.zeros((16, 24, 3), np.float32)  # 16 rows of 24 pixels
    renderer = ssgi.Renderer(ssgi.Scene(CORNELL), size=image)
    assert renderer.size == (24, 16) and renderer.render().shape == image.shape
    truth = ssgi.reference(ssgi.Scene(CORNELL), image, mode="ao", spp=1, cache=False)
    assert truth.shape == image.shape


def test_settings_are_a_mutable_mapping():
    scene = ssgi.Scene(CORNELL, {"indirect_vpls": 16})
    settings = scene.settings
    assert isinstance(settings, collections.abc.MutableMapping)
    settings.update({"ao_steps": 3}, shadow_taps=9)
    settings.update([("ao_directions", 4)])
    assert (settings["ao_steps"], settings["shadow_taps"], settings["ao_directions"]) == (3, 9, 4)
    del settings["ao_steps"]  # forgets what Python set: the file's value
    assert settings["ao_steps"] == ssgi.Scene(CORNELL).settings["ao_steps"]
    assert settings.pop("indirect_vpls") == 16
    assert settings["indirect_vpls"] == ssgi.Scene(CORNELL).settings["indirect_vpls"]
    settings.clear()
    assert settings == ssgi.Scene(CORNELL).settings
    assert dict(settings) == settings.to_dict() and len(settings) == len(list(settings))
    with pytest.raises(KeyError):
        del settings["no_such"]
    assert [row["type"] for row in ssgi.settings_table()][:2] == ["float", "int"]


def test_reference_carries_its_samples_and_noise(tmp_path):
    scene = ssgi.Scene(CORNELL)
    truth = ssgi.reference(scene, (12, 8), mode="ao", spp=8, cache=False)
    assert isinstance(truth, ssgi.Image) and isinstance(truth, np.ndarray)
    assert truth.shape == (8, 12, 3) and truth.samples == 8
    figures = ssgi.compare(truth, truth, maps=False)
    assert figures["reference_samples"] == 8
    assert figures["reference_noise"] == truth.noise or (truth.noise is None and
                                                         figures["reference_noise"] is None)
    assert pickle.loads(pickle.dumps(truth)).samples == 8


def test_images_show_themselves_in_a_notebook(tmp_path):
    image = ssgi.Renderer(ssgi.Scene(CORNELL), SIZE).render()
    png = image._repr_png_()
    assert png.startswith(b"\x89PNG")
    (tmp_path / "shown.png").write_bytes(png)
    shown = ssgi.read_image(tmp_path / "shown.png")
    assert np.allclose(shown, np.round(ssgi.tonemap(image) * 255) / 255, atol=1e-6)


def test_write_image_display_encodes_a_png_unless_linear(tmp_path):
    linear = np.full((2, 2, 3), 0.18, np.float32)
    ssgi.write_image(tmp_path / "shown.png", linear)
    ssgi.write_image(tmp_path / "linear.png", linear, linear=True)
    shown = ssgi.read_image(tmp_path / "shown.png")
    assert np.allclose(shown, np.round(ssgi.tonemap(linear) * 255) / 255, atol=1e-6)
    assert np.allclose(ssgi.read_image(tmp_path / "linear.png"), round(0.18 * 255) / 255)
    as_bytes = (ssgi.tonemap(linear) * 255).round().astype(np.uint8)  # display values already
    ssgi.write_image(tmp_path / "bytes.png", as_bytes)
    assert np.array_equal(ssgi.read_image(tmp_path / "bytes.png"), shown)


def test_the_repr_counts_frames_in_english():
    renderer = ssgi.Renderer(ssgi.Scene(CORNELL), SIZE)
    renderer.render()
    assert repr(renderer).endswith(", 1 frame>")
    renderer.render()
    assert repr(renderer).endswith(", 2 frames>")
    assert not any(".unused" in name for name in renderer.images())


def test_python_m_ssgi_runs_the_programs(tmp_path):
    def run(*args):
        return subprocess.run([sys.executable, "-m", "ssgi", *map(str, args)], cwd=tmp_path,
                              capture_output=True, text=True)
    made = run("render", "cornell-box", "--size", "24x16", "--frames", 2, "-o", "r.exr")
    assert made.returncode == 0 and "wrote r.exr" in made.stdout, made.stderr
    assert np.array_equal(ssgi.read_image(tmp_path / "r.exr"),
                          fresh({}).astype(np.float16).astype(np.float32))
    made = run("reference", CORNELL, "--size", "24x16", "--spp", 4, "--set", "ao_radius=0.1",
               "-o", "t.exr")
    assert made.returncode == 0, made.stderr
    compared = run("compare", "r.exr", "t.exr")
    assert compared.returncode == 0 and "relmse:" in compared.stdout, compared.stderr
    unknown = run("render", "nope", "-o", "x.exr")
    assert unknown.returncode == 2 and "no shipped scene named 'nope'" in unknown.stderr
    bad = run("render", "cornell-box", "--set", "indirect_vpls=217.6", "-o", "x.exr")
    assert bad.returncode == 2 and bad.stderr.startswith("error: settings: ")


# Issue 70, class 4: values that came back wrong.

def test_tonemap_of_negative_radiance_is_black():
    image = np.array([[[-1.0, -1e6, 0.0], [np.nan, 1.0, -0.5]]], np.float32)
    shown = ssgi.tonemap(image)
    assert np.array_equal(shown[0, 0], [0, 0, 0])
    assert np.isnan(shown[0, 1, 0]) and shown[0, 1, 2] == 0 and 0 < shown[0, 1, 1] < 1


def test_an_integer_image_reads_as_its_integers():
    renderer = ssgi.Renderer(ssgi.Scene(CORNELL, {"indirect_method": 3}), SIZE)
    renderer.render(frames=2)
    integers = [name for name in renderer.images() if name.startswith("world.")]
    assert "world.voxels" in integers
    for name in integers:
        image = renderer.read(name)
        if image.dtype.kind == "f":
            continue
        assert image.dtype in (np.uint32, np.uint8) and image.ndim == 2, name
    voxels = renderer.read("world.voxels")
    assert voxels.dtype == np.uint32 and voxels.any()
