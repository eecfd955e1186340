"""The Python module's tests: the validation layer on for every device they open, any message it
reports fails the test during which it came, and a skipped test counts as failed."""
import os
import pathlib
import subprocess

os.environ["SSGI_VALIDATION"] = "1"  # read when the first device opens

import pytest  # noqa: E402
import ssgi  # noqa: E402

ROOT = pathlib.Path(__file__).resolve().parents[2]
BUILD = pathlib.Path(os.environ.get("SSGI_BUILD_DIR", ROOT / "build")).resolve()
CORNELL = str(ROOT / "scenes" / "cornell-box.json")


def program(name, *args, cwd=ROOT):
    """Runs build/NAME with `args`; its exit status and its stdout and stderr together. Without
    the validation layer, which the programs' own tests run them with: here they only give the
    files and messages that the module's must equal, and start faster."""
    env = {k: v for k, v in os.environ.items() if k != "SSGI_VALIDATION"}
    run = subprocess.run([str(BUILD / name), *map(str, args)], cwd=cwd, capture_output=True,
                         text=True, env=env)
    return run.returncode, run.stdout + run.stderr


def program_error(name, *args, status=2):
    """The message of the `error: ...` line a program prints for bad input (exit status 2), or
    for a device that fails (1)."""
    exit_status, output = program(name, *args)
    assert exit_status == status, output
    lines = [line for line in output.splitlines() if line.startswith("error: ")]
    assert len(lines) == 1, output
    return lines[0][len("error: "):]


@pytest.fixture(autouse=True)
def no_validation_messages():
    before = ssgi.validation_messages()
    yield
    assert ssgi.validation_messages() == before, "the validation layer reported messages"


@pytest.hookimpl(hookwrapper=True)
def pytest_runtest_makereport(item, call):
    outcome = yield
    report = outcome.get_result()
    if report.skipped:
        report.outcome = "failed"
