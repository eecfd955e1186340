"""The two examples run as a user runs them, and each can fail."""
import ast
import itertools
import math
import os
import subprocess
import sys

import numpy as np
import ssgi
from conftest import ROOT

EXAMPLES = ROOT / "examples"


def run_python(*args, cwd=ROOT):
    run = subprocess.run([sys.executable, *map(str, args)], cwd=cwd, capture_output=True,
                         text=True, env=dict(os.environ, SSGI_VALIDATION="1"))
    assert "validation" not in run.stderr.lower(), run.stderr
    return run


def test_pareto_sweep_draws_the_front(tmp_path):
    script = EXAMPLES / "pareto_sweep.py"
    assert len(script.read_text().splitlines()) < 45
    run = run_python(script, 40, 16, "chart.png", cwd=tmp_path)  # from another folder
    assert run.returncode == 0, run.stdout + run.stderr
    rows = {}  # label -> (on the front, ms, relMSE)
    for line in run.stdout.splitlines()[:-1]:
        mark, rest = line[:5].strip(), line[5:].split(None, 3)
        rows[rest[3]] = (mark == "front", float(rest[0]), float(rest[2]))
    assert len(rows) == 10 and run.stdout.splitlines()[-1].startswith("wrote")
    assert all(ms > 0 and 0 < error and math.isfinite(error) for _, ms, error in rows.values())
    cheapest = min(rows.values(), key=lambda row: row[1])
    assert cheapest[0]  # the cheapest point is always on the front
    # In the example's own order, cheapest first: its times are printed to 0.1 ms, so sorting
    # the printed ones again could swap two points timed within 0.05 ms of each other.
    front = [(ms, error) for on, ms, error in rows.values() if on]
    assert all(b[1] < a[1] for a, b in zip(front, front[1:]))  # the front's error falls
    assert rows["direct only"][2] > rows["defaults"][2]  # the bounce is most of the box's light
    assert (tmp_path / "chart.png").stat().st_size > 10000


def test_every_pareto_configuration_changes_the_image():
    """Each point of the sweep is a configuration that renders another image than every other
    one: none sits on another's spot because its setting changes nothing in the box."""
    tree = ast.parse((EXAMPLES / "pareto_sweep.py").read_text())
    configs = next(ast.literal_eval(node.value) for node in tree.body
                   if isinstance(node, ast.Assign) and ast.unparse(node.targets[0]) == "configs")
    assert len(configs) == 10
    scene = ROOT / "scenes" / "cornell-box.json"
    images = {label: ssgi.Renderer(ssgi.Scene(scene, {"cache": 0, **settings}), (32, 32)).render()
              for label, settings in configs.items()}
    for a, b in itertools.combinations(images, 2):
        assert not np.array_equal(images[a], images[b]), (a, b)


def test_golden_image_example_passes_and_catches_a_change(tmp_path):
    run = run_python("-m", "pytest", "-q", "-p", "no:cacheprovider", EXAMPLES / "test_golden.py",
                     cwd=tmp_path)  # from another folder
    assert run.returncode == 0 and "1 passed" in run.stdout, run.stdout + run.stderr
    sys.path.insert(0, str(EXAMPLES))
    import test_golden
    failed = test_golden.failed_checks(test_golden.render({"world_vpls": 8}))
    assert any(check.startswith("mean FLIP") for check in failed), failed
