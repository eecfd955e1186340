"""The module against the programs: the same images and figures, bit for bit."""
import copy
import re
import threading

import numpy as np
import pytest
import ssgi
from conftest import CORNELL, program


def file_bytes(path):
    """A file's bytes but for the time of writing that OpenImageIO stamps in an EXR's header."""
    return re.sub(rb"\d{4}:\d\d:\d\d \d\d:\d\d:\d\d", b"", path.read_bytes(), count=1)


def test_render_is_the_render_programs_image(tmp_path):
    status, output = program("render", CORNELL, "--frames", 4, "--output", tmp_path / "r.png")
    assert status == 0, output
    renderer = ssgi.Renderer(ssgi.Scene(CORNELL))
    assert renderer.validation
    image = renderer.render(frames=4)
    assert image.dtype == np.float32 and image.shape == (512, 512, 3)
    ssgi.write_image(tmp_path / "p.exr", image)
    ssgi.write_image(tmp_path / "p.png", renderer.read("ldr"), linear=True)  # display values
    assert file_bytes(tmp_path / "p.exr") == file_bytes(tmp_path / "r.exr")
    assert file_bytes(tmp_path / "p.png") == file_bytes(tmp_path / "r.png")
    # The EXR holds half floats: the array is what they were rounded from.
    stored = ssgi.read_image(tmp_path / "r.exr")
    assert np.array_equal(stored, image.astype(np.float16).astype(np.float32))
    assert image.min() >= 0 and image.max() > 0.1


def test_reference_is_the_reference_programs_image(tmp_path):
    cache = tmp_path / "cache"
    # The module's defaults are the program's: the same noise target, so the same cache entry.
    status, output = program("reference", CORNELL, "--mode", "ao", "--size", "24x16", "--spp", 8,
                             "--cache", cache, "--output", tmp_path / "r.exr", "--quiet")
    assert status == 0, output
    cached = list(cache.iterdir())
    scene = ssgi.Scene(CORNELL)
    # From the program's cache entry, then rendered anew: the same image both ways.
    from_cache = ssgi.reference(scene, mode="ao", size=(24, 16), spp=8, cache_dir=cache)
    rendered = ssgi.reference(scene, mode="ao", size=(24, 16), spp=8, cache=False)
    assert list(cache.iterdir()) == cached
    assert from_cache.shape == (16, 24, 3)
    assert np.array_equal(from_cache, rendered)
    # The same pixels; the program's header also records the samples and the noise.
    ssgi.write_image(tmp_path / "p.exr", rendered)
    assert np.array_equal(ssgi.read_image(tmp_path / "p.exr"), ssgi.read_image(tmp_path / "r.exr"))
    assert ssgi.compare(rendered, tmp_path / "r.exr", maps=False)["reference_samples"] == 8
    assert ssgi.compare(rendered, tmp_path / "p.exr", maps=False)["reference_noise"] is None
    assert 0.2 < rendered.mean() < 1.0  # AO: most of the box is open


def test_compare_gives_the_compare_programs_figures(tmp_path):
    import json
    scene = ssgi.Scene(CORNELL)
    scene.settings["indirect_method"] = 1  # the screen-space bounce, which reads indirect_vpls
    ssgi.write_image(tmp_path / "a.exr", ssgi.Renderer(scene, (64, 48)).render())
    scene.settings["indirect_vpls"] = 16
    ssgi.write_image(tmp_path / "b.exr", ssgi.Renderer(scene, (64, 48)).render())
    status, output = program("compare", tmp_path / "a.exr", tmp_path / "b.exr", "--max-diff", 2,
                             "--json", tmp_path / "c.json")
    assert status == 1 and "FAIL: fraction" in output, output  # the threshold 0 is exceeded
    expected = json.loads((tmp_path / "c.json").read_text())
    region = expected["regions"][0]
    a, b = ssgi.read_image(tmp_path / "a.exr"), ssgi.read_image(tmp_path / "b.exr")
    for figures in (ssgi.compare(tmp_path / "a.exr", tmp_path / "b.exr", max_diff=2),
                    ssgi.compare(a, b, max_diff=2)):
        assert figures["relmse"] == region["relmse"] and region["relmse"] > 0
        assert figures["rmse"] == region["rmse"] and figures["mae"] == region["mae"]
        assert figures["ssim"] == region["ssim"] and figures["flip"] == expected["flip"]
        assert figures["diff_fraction"] == expected["diff_fraction"]
        maps = figures["maps"]
        assert maps["flip"].shape == (48, 64) and maps["error_map"].shape == (48, 64, 3)
        assert maps["flip"].mean() == pytest.approx(expected["flip"], rel=1e-12)
    same = ssgi.compare(a, a)
    assert same["relmse"] == 0 and same["flip"] == 0 and same["ssim"] == pytest.approx(1)


def test_settings_are_the_settings_table():
    scene = ssgi.Scene(CORNELL)
    table = ssgi.settings_table()
    assert list(scene.settings) == [row["name"] for row in table] and len(scene.settings) > 40
    for row in table:
        value = scene.settings[row["name"]]
        assert type(value) is {"bool": bool, "int": int, "float": float}[row["type"]]
    scene.settings["ao_steps"] = 2
    scene.settings = {"cache": False, "exposure": 0.5}
    assert (scene.settings["ao_steps"], scene.settings["cache"]) == (2, False)
    assert scene.settings.to_dict()["exposure"] == 0.5 and "exposure" in scene.settings
    given = ssgi.Scene(CORNELL, settings={"ao_steps": 2})
    assert given.settings["ao_steps"] == 2


def test_a_renderer_follows_its_scene_and_a_copy_keeps_it_as_it_was():
    scene = ssgi.Scene(CORNELL)
    kept = ssgi.Renderer(copy.copy(scene), (32, 32))  # a scene of its own
    following = ssgi.Renderer(scene, (32, 32))
    scene.settings["exposure"] = 2.0
    kept.render()
    following.render()
    assert following.read("ldr")[..., :3].mean() > kept.read("ldr")[..., :3].mean() + 0.05
    assert kept.settings["exposure"] == 1.0 and following.settings["exposure"] == 2.0


def test_every_view_renders():
    renderer = ssgi.Renderer(ssgi.Scene(CORNELL), (32, 24))
    final = renderer.render()
    for view in ssgi.view_names():
        image = renderer.render(view=view)
        assert image.shape == (24, 32, 3) and np.isfinite(image).all(), view
        assert renderer.view == view
    assert not np.array_equal(renderer.render(view="normal"), final)


def test_time_camera_cut_profile_memory():
    renderer = ssgi.Renderer(ssgi.Scene(CORNELL), (48, 48))
    first = renderer.render()
    renderer.set_camera(position=[0, 1, 2.5], target=(0, 1, 0), fov=50)
    assert renderer.camera["fov"] == pytest.approx(50)
    assert renderer.camera["forward"] == pytest.approx([0, 0, -1], abs=1e-6)
    moved = renderer.render()
    assert not np.array_equal(first, moved)
    renderer.cut()
    renderer.render()
    assert renderer.cuts >= 1
    renderer.set_time(1.0)
    renderer.render()
    profile = renderer.profile()
    assert {"gbuffer", "direct", "composite"} <= set(profile["passes"])
    assert profile["host_ms"] > 0 and profile["sum_ms"] == pytest.approx(
        sum(profile["passes"].values()))
    memory = renderer.memory()
    assert memory["held_bytes"] > 0 and "hdr" in memory["images"]
    assert renderer.read("gbuffer.normal").shape == (48, 48, 4)


def test_tonemap_is_the_composites_display_transform():
    renderer = ssgi.Renderer(ssgi.Scene(CORNELL), (64, 64))
    shown = ssgi.tonemap(renderer.render())
    ldr = renderer.read("ldr")[..., :3]
    assert np.abs(np.round(shown * 255) - np.round(ldr * 255)).max() <= 1


def test_images_round_trip(tmp_path):
    image = np.random.default_rng(1).random((5, 7, 3), dtype=np.float32)
    ssgi.write_image(tmp_path / "a.exr", image * 1e5)  # beyond half: stored as 32-bit floats
    assert np.array_equal(ssgi.read_image(tmp_path / "a.exr"), image * np.float32(1e5))
    ssgi.write_image(str(tmp_path / "a.png"), image, linear=True)
    assert np.abs(ssgi.read_image(tmp_path / "a.png") - image).max() <= 0.5 / 255 + 1e-6
    assert ssgi.read_image(tmp_path / "a.png", alpha=True).shape == (5, 7, 4)


def test_rendering_releases_the_gil():
    renderer = ssgi.Renderer(ssgi.Scene(CORNELL), (128, 128))
    renderer.render()
    worker = threading.Thread(target=renderer.render, kwargs={"frames": 4})
    count = 0
    worker.start()
    while worker.is_alive():
        count += 1
    worker.join()
    assert count > 10000  # this thread ran while the other rendered
