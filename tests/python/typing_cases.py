"""Every argument type the module accepts, as a user writes it: test_typing.py runs it (the module
takes each) and checks it with mypy against the stub (the stub takes each)."""
import pathlib

import numpy as np
import ssgi


def run(cornell: pathlib.Path, folder: pathlib.Path) -> None:
    scene = ssgi.Scene(cornell, settings={"ao_radius": np.float32(0.25), "cache": np.bool_(True),
                                          "ao_steps": np.int64(3), "shadow_taps": 9})
    scene = ssgi.Scene(str(cornell), {"exposure": 1.5})
    scene.settings["ao_radius"] = np.float32(0.25)
    scene.settings["indirect_vpls"] = np.int64(32)
    scene.settings["indirect"] = np.bool_(True)
    scene.settings.update({"exposure": np.float64(1.0)})
    scene.settings.update({"ao_steps": 4})  # (mypy 1.0 types `scene.settings = {...}` by the getter)
    value: "bool | int | float" = scene.settings["ao_steps"]
    assert value == 4
    shipped = ssgi.Scene(ssgi.scene_file("cornell-box"))
    floor = {"type": "quad", "material": "white", "corners": [[0, 0, 0], [1, 0, 0], [1, 0, 1],
                                                             [0, 0, 1]]}
    ssgi.Scene.from_dict({"materials": {"white": {"albedo": [0.8, 0.8, 0.8]}}, "objects": [floor]},
                         base=folder, settings={"exposure": 2})
    with ssgi.Renderer(shipped, size=(np.int64(16), 16), device=None, view="final",
                       keep=["ao"]) as renderer:
        renderer.settings["indirect_vpls"] = np.int32(16)
        renderer.set_camera(position=np.array([0.3, 0.3, -0.7]), target=(np.float32(0.3), 0.3, 0),
                            up=[0, 1, 0], fov=np.float32(40))
        renderer.set_light(position=(0.3, 0.5, 0.3), direction=(0, -1, 0), color=(1, 1, 1),
                           intensity=np.float64(2), cone=60, inner_cone=np.int64(20), radius=0)
        renderer.set_time(np.float32(0.5))
        image: np.ndarray = renderer.render(frames=np.int64(2), view=None)
        assert renderer.read("hdr").shape == (16, 16, 4)
    ssgi.write_image(folder / "a.png", image, linear=np.bool_(False), exposure=np.float32(2))
    ssgi.write_image(str(folder / "a.exr"), ssgi.tonemap(image, exposure=np.int64(1)))
    truth = ssgi.reference(scene, (np.int64(8), 8), mode="ao", spp=np.uint16(4),
                           noise=np.float32(0), seed=np.int8(1), time=None, jitter=np.bool_(False),
                           light_radius=np.float32(0.01), threads=np.int64(1),
                           cache=False, cache_dir=folder, progress=lambda done, spp, noise: None)
    samples = truth.samples
    assert samples == 4 and truth.noise is None or isinstance(truth.noise, float)
    figures = ssgi.compare(image[:8, :8], truth, exposure=np.float32(1), ppd=np.int64(67),
                           max_diff=np.float64(2), linear=np.bool_(True), maps=False)
    assert figures["pixels"] == 64
    ssgi.compare(folder / "a.png", str(folder / "a.png"))
    assert ssgi.read_image(folder / "a.exr", alpha=np.bool_(True)).shape == (16, 16, 4)
