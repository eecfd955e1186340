"""Ctrl-C stops render(frames=N) between frames and reference() between (and within) its passes
with KeyboardInterrupt, leaving the renderer usable; reference() reports its progress."""
import os
import signal
import threading
import time

import numpy as np
import pytest
import ssgi
from conftest import CORNELL


def test_ctrl_c_stops_a_long_render_within_one_frame():
    renderer = ssgi.Renderer(ssgi.Scene(CORNELL), size=(32, 32))
    renderer.render()  # the first frame compiles the shader variants
    sent = {}

    def interrupt():
        while renderer.frames < 6:
            time.sleep(0.001)
        os.kill(os.getpid(), signal.SIGINT)
        sent["frames"], sent["at"] = renderer.frames, time.perf_counter()

    start = time.perf_counter()
    thread = threading.Thread(target=interrupt)
    thread.start()
    with pytest.raises(KeyboardInterrupt):
        renderer.render(frames=200)
    stopped = time.perf_counter()
    thread.join()
    # The frame under way when the signal came is finished; no other is started.
    assert renderer.frames <= sent["frames"] + 1 and renderer.frames < 201
    frame_s = (sent["at"] - start) / (sent["frames"] - 1)
    print(f"stopped {1e3 * (stopped - sent['at']):.1f} ms after the signal; a frame takes "
          f"{1e3 * frame_s:.1f} ms; {renderer.frames - 1} of 200 frames rendered")
    # Usable afterwards: it renders, and what it renders is the renderer's image.
    done = renderer.frames
    image = renderer.render(frames=2)
    assert renderer.frames == done + 2 and image.shape == (32, 32, 3) and image.max() > 0
    assert renderer.read("ldr").shape == (32, 32, 4)


def test_ctrl_c_stops_the_reference_and_caches_nothing(tmp_path):
    scene = ssgi.Scene(CORNELL)
    calls, sent, threads = [], [], []

    def interrupt():
        os.kill(os.getpid(), signal.SIGINT)
        sent.append(len(calls))

    def progress(samples, spp, noise):
        calls.append(samples)
        if len(calls) == 3:
            threads.append(threading.Thread(target=interrupt))
            threads[0].start()

    with pytest.raises(KeyboardInterrupt):
        ssgi.reference(scene, size=(64, 64), spp=1 << 20, cache_dir=tmp_path, progress=progress)
    threads[0].join()
    # The next check (every 10 ms) raises: at most a call already under way came after.
    assert len(calls) <= sent[0] + 1
    assert list(tmp_path.iterdir()) == []  # nothing half-rendered was stored
    image = ssgi.reference(scene, mode="ao", size=(8, 8), spp=4, cache_dir=tmp_path)
    assert image.shape == (8, 8, 3) and len(list(tmp_path.iterdir())) == 1


def test_an_exception_in_the_progress_callback_stops_the_reference():
    def progress(samples, spp, noise):
        raise RuntimeError("enough")

    with pytest.raises(RuntimeError, match="enough"):
        ssgi.reference(ssgi.Scene(CORNELL), size=(16, 16), spp=64, cache=False,
                       progress=progress)


def test_reference_reports_its_progress(capfd):
    scene = ssgi.Scene(CORNELL)
    calls = []
    image = ssgi.reference(scene, size=(24, 24), spp=32, cache=False,
                           progress=lambda *args: calls.append(args))
    samples = [c[0] for c in calls]
    assert len(calls) >= 2 and samples == sorted(samples) and samples[-1] == 32
    assert all(spp == 32 for _, spp, _ in calls) and np.isfinite(calls[-1][2])
    again = ssgi.reference(scene, size=(24, 24), spp=32, cache=False, progress=False)
    assert np.array_equal(image, again)  # watching does not change the image
    assert capfd.readouterr().err == ""
    ssgi.reference(scene, size=(24, 24), spp=32, cache=False, progress=True)
    assert "32" in capfd.readouterr().err  # reference's own bar
    with pytest.raises(TypeError, match=r"progress: expected True, False, None or a callable of "
                                        r"\(samples, spp, noise\), got 'yes' \(str\)"):
        ssgi.reference(scene, size=(4, 4), spp=1, cache=False, progress="yes")
