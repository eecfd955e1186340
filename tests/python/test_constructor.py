"""What a renderer is made with (its view, size and settings) is what it renders until changed."""
import numpy as np
import ssgi
from conftest import CORNELL


def test_the_view_given_to_the_constructor_is_rendered():
    scene = ssgi.Scene(CORNELL)
    albedo = ssgi.Renderer(scene, size=(32, 24), view="albedo")
    assert albedo.view == "albedo"
    image = albedo.render()
    assert albedo.view == "albedo"  # render() without a view keeps the renderer's
    switched = ssgi.Renderer(scene, size=(32, 24))
    assert np.array_equal(switched.render(view="albedo"), image)
    final = ssgi.Renderer(scene, size=(32, 24)).render()
    assert not np.array_equal(image, final)
    # A view given to render() holds from then on, as the constructor's did.
    albedo.render(view="final")
    assert albedo.view == "final"
    assert not np.array_equal(albedo.render(), image) and albedo.view == "final"


def test_size_and_settings_hold_until_changed():
    scene = ssgi.Scene(CORNELL, settings={"exposure": 0.5})
    renderer = ssgi.Renderer(scene, size=(40, 20))
    dim = renderer.render()
    assert dim.shape == (20, 40, 3) and renderer.size == (40, 20)
    dim_ldr = renderer.read("ldr")[..., :3].mean()
    scene.settings["exposure"] = 2.0  # a change of its scene: the renderer's next frame has it
    renderer.render()
    assert renderer.size == (40, 20) and renderer.view == "final"
    assert dim_ldr + 0.05 < renderer.read("ldr")[..., :3].mean()
