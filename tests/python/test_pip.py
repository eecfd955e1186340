"""`pip install --no-build-isolation .` from a clone of the repository into a fresh virtual
environment (with the system's packages: NumPy, setuptools), with nothing downloaded; then the
package imports from another folder and renders. Slow: it builds the module's libraries."""
import os
import shutil
import subprocess
import sys

import numpy as np
from conftest import BUILD, ROOT

# The clone is refreshed on every run but its CMake build folder is kept: a rerun rebuilds what
# changed, the first run everything.
CLONE = BUILD / "pip-clone"


def repository_files():
    """What a clone holds: the tracked and unignored files (every file but the build folders
    where the tree is no git checkout)."""
    listed = subprocess.run(["git", "ls-files", "-co", "--exclude-standard"], cwd=ROOT,
                            capture_output=True, text=True)
    if listed.returncode == 0:
        names = listed.stdout.splitlines()
    else:
        names = [str(p.relative_to(ROOT)) for p in ROOT.rglob("*") if p.is_file()]
    return [f for f in names if (ROOT / f).is_file() and not f.startswith(("build", "."))
            and "__pycache__" not in f]


def clone_of_the_repository():
    files = repository_files()
    if CLONE.exists():
        for entry in CLONE.iterdir():
            if entry.name != "build-pip":
                shutil.rmtree(entry) if entry.is_dir() else entry.unlink()
    for name in files:
        (CLONE / name).parent.mkdir(parents=True, exist_ok=True)
        shutil.copy2(ROOT / name, CLONE / name)  # times kept: the build sees what changed
    return CLONE


def test_pip_installs_the_package_into_a_virtual_environment(tmp_path):
    source = clone_of_the_repository()
    venv = tmp_path / "venv"
    subprocess.run([sys.executable, "-m", "venv", "--system-site-packages", str(venv)],
                   check=True)
    env = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "SSGI_BUILD_DIR")}
    env.setdefault("CMAKE_BUILD_PARALLEL_LEVEL", "2")
    install = subprocess.run([str(venv / "bin" / "pip"), "install", "--no-build-isolation",
                              "--no-index", "--no-cache-dir", "."], cwd=source,
                             capture_output=True, text=True, env=env)
    assert install.returncode == 0, install.stdout[-4000:] + install.stderr[-4000:]
    assert "Successfully installed ssgi-" in install.stdout
    elsewhere = tmp_path / "elsewhere"
    elsewhere.mkdir()
    python = str(venv / "bin" / "python")
    version = subprocess.run([python, "-c", "import ssgi; print(ssgi.__version__)"],
                             cwd=elsewhere, capture_output=True, text=True, env=env)
    assert version.returncode == 0, version.stderr
    import ssgi
    assert version.stdout.strip() == ssgi.__version__
    script = ("import ssgi, numpy, pathlib, sys\n"
              "assert pathlib.Path(ssgi.__file__).with_suffix('.pyi').exists()\n"
              "assert str(pathlib.Path(ssgi.__file__)).startswith(sys.prefix)\n"
              "assert str(ssgi.scene_file('cornell-box')).startswith(sys.prefix)\n"
              "scene = ssgi.Scene(ssgi.scene_file('cornell-box'))  # shipped in the wheel\n"
              "image = ssgi.Renderer(scene, size=(16, 16)).render()\n"
              "numpy.save(sys.argv[2], image)\n")
    rendered = subprocess.run([python, "-c", script, str(ROOT / "scenes" / "cornell-box.json"),
                               str(tmp_path / "image.npy")], cwd=elsewhere, capture_output=True,
                              text=True, env=env)
    assert rendered.returncode == 0, rendered.stderr
    image = np.load(tmp_path / "image.npy")
    assert image.shape == (16, 16, 3) and np.isfinite(image).all() and image.max() > 0.05
