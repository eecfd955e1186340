"""Builds the package `ssgi` for the Python that runs it: CMake configures the project for this
interpreter (-DPython3_EXECUTABLE) in build-pip/ (SSGI_PIP_BUILD_DIR), builds the target
ssgi_python, and the package it makes (python/ssgi/ with the compiled _ssgi) is what the wheel
holds, with the shipped scenes (scenes/, for ssgi.scene_file()). Run through pip: `pip install --no-build-isolation .` (pyproject.toml)."""
import os
import pathlib
import re
import shutil
import subprocess
import sys

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

ROOT = pathlib.Path(__file__).resolve().parent


def version():
    """The project's version, from CMakeLists.txt's project() (its one place)."""
    text = (ROOT / "CMakeLists.txt").read_text()
    return re.search(r"project\(ssgi VERSION ([0-9.]+)", text).group(1)


class CMakeBuild(build_ext):
    def build_extension(self, ext):
        build = pathlib.Path(os.environ.get("SSGI_PIP_BUILD_DIR", ROOT / "build-pip")).resolve()
        configure = ["cmake", "-S", str(ROOT), "-B", str(build), "-DCMAKE_BUILD_TYPE=Release",
                     f"-DPython3_EXECUTABLE={sys.executable}"]
        if shutil.which("ninja"):
            configure += ["-G", "Ninja"]
        if shutil.which("ccache"):
            configure += ["-DCMAKE_CXX_COMPILER_LAUNCHER=ccache",
                          "-DCMAKE_C_COMPILER_LAUNCHER=ccache"]
        subprocess.run(configure, check=True)
        subprocess.run(["cmake", "--build", str(build), "--target", "ssgi_python"], check=True)
        # The package as the build made it: __init__.py, the stub, _build.py and _ssgi.
        package = build / "python" / "ssgi"
        target = pathlib.Path(self.get_ext_fullpath(ext.name)).parent
        target.mkdir(parents=True, exist_ok=True)
        for file in package.iterdir():
            if file.is_file():
                shutil.copy2(file, target / file.name)
        # The shipped scenes and their models go with the package (ssgi.scene_file()).
        shutil.copytree(ROOT / "scenes", target / "scenes", dirs_exist_ok=True)


setup(
    version=version(),
    packages=["ssgi"],
    package_dir={"": "python"},
    ext_modules=[Extension("ssgi._ssgi", sources=[])],
    cmdclass={"build_ext": CMakeBuild},
    package_data={"ssgi": ["__init__.pyi", "py.typed"]},
    options={"build": {"build_base": str(ROOT / "build-pip" / "setuptools")}},
)
