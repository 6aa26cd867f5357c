"""Builds the two extension modules with the project's CMake (python/CMakeLists.txt) rather than
with setuptools' compiler: they link the C++ libraries the project builds."""

import os
import shutil
import subprocess
import sys
from pathlib import Path

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

ROOT = Path(__file__).resolve().parent
TARGETS = {"lightsampler": "lightsampler_python", "trs_render": "trs_render_python"}


class CMakeBuild(build_ext):
    def run(self):
        build = Path(self.build_temp).resolve() / "cmake"
        subprocess.run(["cmake", "-S", str(ROOT), "-B", str(build), "-G", "Ninja", "-DCMAKE_BUILD_TYPE=Release",
                        f"-DPython3_EXECUTABLE={sys.executable}", "-DLIGHTSAMPLER_BUILD_TESTS=OFF"], check=True)
        subprocess.run(["cmake", "--build", str(build), "--target", *TARGETS.values(),
                        "--parallel", str(os.cpu_count() or 1)], check=True)
        for ext in self.extensions:
            built = next((build / "python").glob(ext.name + ".*.so"))
            destination = Path(self.get_ext_fullpath(ext.name))
            destination.parent.mkdir(parents=True, exist_ok=True)
            shutil.copyfile(built, destination)


setup(
    ext_modules=[Extension(name, sources=[]) for name in TARGETS],
    cmdclass={"build_ext": CMakeBuild},
    # Not build/: that is the CMake build of the README's commands.
    options={"build": {"build_base": "build-pip"}},
)
