"""Builds polyvol._polyvol with the project's CMake (as pybind11's
cmake_example does) and installs it with the package python/polyvol."""

import os
import pathlib
import shutil
import subprocess
import sys

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

ROOT = pathlib.Path(__file__).resolve().parent


class CMakeExtension(Extension):
    def __init__(self, name):
        super().__init__(name, sources=[])


class CMakeBuild(build_ext):
    def build_extension(self, ext):
        target = pathlib.Path(self.get_ext_fullpath(ext.name)).resolve()
        build = pathlib.Path(self.build_temp).resolve() / "cmake"
        build.mkdir(parents=True, exist_ok=True)
        jobs = os.environ.get("CMAKE_BUILD_PARALLEL_LEVEL", str(os.cpu_count() or 2))
        subprocess.run(["cmake", "-S", str(ROOT), "-B", str(build), "-DCMAKE_BUILD_TYPE=Release",
                        f"-DPython_EXECUTABLE={sys.executable}", "-DPOLYVOL_TESTS=OFF", "-DPOLYVOL_BENCH=OFF",
                        "-DPOLYVOL_PYTHON=ON", "-DPOLYVOL_WERROR=OFF"], check=True)
        subprocess.run(["cmake", "--build", str(build), "--target", "_polyvol", "-j", jobs], check=True)
        built = next((build / "python" / "polyvol").glob("_polyvol*.so"))
        target.parent.mkdir(parents=True, exist_ok=True)
        shutil.copyfile(built, target)


setup(
    packages=["polyvol"],
    package_dir={"polyvol": "python/polyvol"},
    ext_modules=[CMakeExtension("polyvol._polyvol")],
    cmdclass={"build_ext": CMakeBuild},
    zip_safe=False,
)
