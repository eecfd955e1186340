"""A golden-image test for pytest, to copy into a project's CI: render a scene at 256x256 on the
CPU (lavapipe) and compare it with an image stored beside this file, with thresholds.

    PYTHONPATH=build/python python3 -m pytest examples/test_golden.py

Refresh the golden image when a change of the picture is intended (on the CI image itself):

    SSGI_UPDATE_GOLDEN=1 PYTHONPATH=build/python python3 -m pytest examples/test_golden.py
"""
import os
import pathlib
from typing import List, Mapping, Optional

import ssgi

GOLDEN = pathlib.Path(__file__).resolve().parent / "golden" / "cornell-box-256.exr"
SCENE = ssgi.scene_file("cornell-box")  # the shipped scene, from any folder
FRAMES = 16  # the temporal cache makes frame 16 differ from frame 1: keep the count fixed
# Filament's render-diff pair (at most 0.1% of the pixels off by more than 5 of 255 in the
# display image), mean FLIP and relMSE (ci-golden-images.md).
MAX_DIFF, MAX_FRACTION, MAX_FLIP, MAX_RELMSE = 5, 0.001, 0.01, 0.001


def render(settings: Optional[Mapping[str, float]] = None) -> ssgi.Image:
    scene = ssgi.Scene(SCENE, settings or {})
    return ssgi.Renderer(scene, size=(256, 256), device="llvmpipe").render(frames=FRAMES)


def failed_checks(image: ssgi.Image, golden: pathlib.Path = GOLDEN) -> List[str]:
    """The thresholds `image` exceeds against the golden image, as 'name value > limit'."""
    figures = ssgi.compare(image, ssgi.read_image(golden), max_diff=MAX_DIFF, maps=False)
    checks = [("fraction off by more than %d/255" % MAX_DIFF, "diff_fraction", MAX_FRACTION),
              ("mean FLIP", "flip", MAX_FLIP), ("relMSE", "relmse", MAX_RELMSE)]
    return ["%s %.4g > %g" % (name, figures[key], limit)
            for name, key, limit in checks if not figures[key] <= limit]  # NaN fails


def test_cornell_box_matches_golden_image() -> None:
    image = render()
    if os.environ.get("SSGI_UPDATE_GOLDEN") == "1":
        GOLDEN.parent.mkdir(exist_ok=True)
        ssgi.write_image(GOLDEN, image)
    assert GOLDEN.exists(), "no golden image: run once with SSGI_UPDATE_GOLDEN=1"
    assert failed_checks(image) == []
