"""The stub is as wide as the module: what the module takes (NumPy's numbers among them), mypy
takes with the stub, in the examples and in typing_cases.py, which also runs; and stubtest finds
the stub and the module alike."""
import os
import pathlib
import subprocess
import sys

import ssgi
import typing_cases
from conftest import CORNELL, ROOT

HERE = pathlib.Path(__file__).resolve().parent


def mypy(*args):
    env = dict(os.environ, MYPYPATH=str(pathlib.Path(ssgi.__file__).parent.parent))
    return subprocess.run([sys.executable, "-m", "mypy", "--no-incremental",
                           "--ignore-missing-imports", "--strict-equality", *map(str, args)],
                          capture_output=True, text=True, env=env)


def test_the_module_takes_every_case(tmp_path):
    typing_cases.run(pathlib.Path(CORNELL), tmp_path)


def test_mypy_takes_every_case_and_the_examples():
    checked = mypy(HERE / "typing_cases.py", *sorted((ROOT / "examples").glob("*.py")))
    assert checked.returncode == 0, checked.stdout + checked.stderr


def test_mypy_refuses_what_the_module_refuses(tmp_path):
    wrong = tmp_path / "wrong.py"
    wrong.write_text("import ssgi\nssgi.Renderer(ssgi.Scene('x'), size='big')\n"
                     "ssgi.tonemap('image.png')\n")
    checked = mypy(wrong)
    assert checked.returncode == 1 and checked.stdout.count("error:") == 2, checked.stdout


def test_stubtest_finds_the_stub_and_the_module_alike():
    env = dict(os.environ, MYPYPATH=str(pathlib.Path(ssgi.__file__).parent.parent))
    run = subprocess.run([sys.executable, "-m", "mypy.stubtest", "ssgi", "--allowlist",
                          str(HERE / "stubtest_allowlist.txt")],
                         capture_output=True, text=True, env=env)
    assert run.returncode == 0, run.stdout + run.stderr
