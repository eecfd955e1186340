"""`cmake --install` puts the package where Debian's python3 finds it, and a Python it was not
built for is told so at import."""
import os
import shutil
import subprocess
import sys
import sysconfig

import ssgi
from conftest import BUILD

PACKAGE = BUILD / "python" / "ssgi"


def run(*args, cwd, env=None):
    return subprocess.run([str(a) for a in args], cwd=cwd, capture_output=True, text=True,
                          env=env)


def test_cmake_install_puts_the_package_where_python_finds_it(tmp_path):
    status = run("cmake", "--install", BUILD, "--prefix", tmp_path / "prefix", cwd=tmp_path)
    assert status.returncode == 0, status.stdout + status.stderr
    version = f"python{sys.version_info.major}.{sys.version_info.minor}"
    installed = tmp_path / "prefix" / "lib" / version / "dist-packages" / "ssgi"
    assert sorted(p.name for p in installed.iterdir()) == sorted(
        [p.name for p in PACKAGE.iterdir() if p.name != "__pycache__"] + ["scenes"])
    # Under the default prefix that folder is on Debian's python3's path.
    if sys.executable == "/usr/bin/python3":
        assert f"/usr/local/lib/{version}/dist-packages" in sys.path
    elsewhere = tmp_path / "elsewhere"
    elsewhere.mkdir()
    env = dict(os.environ, PYTHONPATH=str(installed.parent))
    imported = run(sys.executable, "-c", "import ssgi; print(ssgi.__version__, ssgi.__file__)",
                   cwd=elsewhere, env=env)
    assert imported.returncode == 0, imported.stderr
    assert imported.stdout.split() == [ssgi.__version__, str(installed / "__init__.py")]
    # The shipped scenes are installed with it: the docs' examples load them from anywhere.
    loaded = run(sys.executable, "-c", "import ssgi; print(ssgi.scene_file('cornell-box')); "
                 "ssgi.Scene(ssgi.scene_file('cornell-box-mesh'))", cwd=elsewhere, env=env)
    assert loaded.returncode == 0, loaded.stderr
    assert loaded.stdout.strip() == str(installed / "scenes" / "cornell-box.json")


def test_a_python_without_numpy_is_told_at_import(tmp_path):
    """A virtual environment without the system's packages: NumPy is missing. The import says
    so, naming the Python ssgi was built for, instead of failing at the first render."""
    status = run(sys.executable, "-m", "venv", "--without-pip", tmp_path / "venv", cwd=tmp_path)
    assert status.returncode == 0, status.stderr
    python = tmp_path / "venv" / "bin" / "python"
    env = dict(os.environ, PYTHONPATH=str(PACKAGE.parent))
    imported = run(python, "-c", "import ssgi", cwd=tmp_path, env=env)
    assert imported.returncode == 1
    message = imported.stderr.strip().splitlines()[-1]
    assert message.startswith(f"ImportError: ssgi {ssgi.__version__} was built for Python "
                              f"{sys.version_info.major}.{sys.version_info.minor}"), message
    assert "cannot import NumPy" in message and "--system-site-packages" in message


def test_a_python_of_another_version_is_told_at_import(tmp_path):
    """The compiled module carries its Python's ABI in its name; another Python finds no
    module it can load, and the import says which Python to use or how to build for this one."""
    package = tmp_path / "ssgi"
    shutil.copytree(PACKAGE, package)
    suffix = sysconfig.get_config_var("EXT_SUFFIX")
    compiled = package / f"_ssgi{suffix}"
    compiled.rename(package / "_ssgi.cpython-399-x86_64-linux-gnu.so")  # as 3.99 would name it
    env = dict(os.environ, PYTHONPATH=str(tmp_path))
    imported = run(sys.executable, "-c", "import ssgi", cwd=tmp_path, env=env)
    assert imported.returncode == 1
    message = imported.stderr.strip().splitlines()[-1]
    assert "its compiled module (_ssgi" in message and "is not one this Python loads" in message
    assert "pip install --no-build-isolation ." in message, message
