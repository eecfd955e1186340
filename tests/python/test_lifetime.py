"""close() and the context-manager protocol give a renderer's device memory back; its repr says
what it renders and where."""
import pytest
import ssgi
from conftest import CORNELL


def test_with_closes_the_renderer():
    scene = ssgi.Scene(CORNELL)
    with ssgi.Renderer(scene, size=(24, 16)) as renderer:
        assert isinstance(renderer, ssgi.Renderer) and not renderer.closed
        assert renderer.render().shape == (16, 24, 3)
    assert renderer.closed
    for call in (renderer.render, renderer.cut, renderer.profile, renderer.memory,
                 renderer.images, lambda: renderer.read("hdr"), lambda: renderer.size,
                 lambda: renderer.set_time(0.0), lambda: renderer.set_camera(fov=40)):
        with pytest.raises(ValueError, match="this renderer is closed"):
            call()
    renderer.close()  # again: nothing to do
    assert renderer.frames == 1 and renderer.view == "final"  # what it was stays readable


def test_an_exception_in_the_with_block_closes_it_and_goes_on():
    with pytest.raises(ZeroDivisionError):
        with ssgi.Renderer(ssgi.Scene(CORNELL), size=(16, 16)) as renderer:
            renderer.render()
            1 / 0
    assert renderer.closed


def test_repr_says_scene_size_view_and_device():
    renderer = ssgi.Renderer(ssgi.Scene(CORNELL), size=(40, 30), view="normal")
    text = repr(renderer)
    assert text.startswith("<ssgi.Renderer of '") and "cornell-box.json" in text
    assert "at 40x30" in text and "view 'normal'" in text and renderer.device in text
    assert "0 frames" in text
    renderer.close()
    assert repr(renderer).endswith(", closed>")
    assert repr(ssgi.Scene(CORNELL, settings={"ao": False})).endswith(
        "cornell-box.json', settings={'ao': False})")
