"""Builds the Python module geotex with the project's CMake for the interpreter running this
script (pip install --no-build-isolation .): configures the tree with the tests and
benchmarks off, builds the one target geotex_python and puts the extension beside the
package's Python files (python/geotex). GEOTEX_CMAKE_ARGS adds configure arguments."""

import os
import shlex
import shutil
import subprocess
import sys
from pathlib import Path

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

ROOT = Path(__file__).resolve().parent


class CMakeBuild(build_ext):
    def build_extension(self, ext):
        build = Path(self.build_temp).resolve() / "cmake"
        args = [
            "-S", str(ROOT), "-B", str(build),
            "-DCMAKE_BUILD_TYPE=Release",
            f"-DPython3_EXECUTABLE={sys.executable}",
            "-DGEOTEX_BUILD_TESTS=OFF", "-DGEOTEX_BUILD_BENCH=OFF",
        ]
        if shutil.which("ninja"):
            args += ["-G", "Ninja"]
        if shutil.which("ccache"):
            args.append("-DCMAKE_CXX_COMPILER_LAUNCHER=ccache")
        args += shlex.split(os.environ.get("GEOTEX_CMAKE_ARGS", ""))
        subprocess.run(["cmake", *args], check=True)
        jobs = os.environ.get("CMAKE_BUILD_PARALLEL_LEVEL", str(min(os.cpu_count() or 1, 2)))
        subprocess.run(["cmake", "--build", str(build), "--target", "geotex_python", "-j", jobs], check=True)
        built = sorted((build / "python" / "geotex").glob("_geotex*.so"))
        if not built:
            raise RuntimeError(
                "geotex: CMake did not build the Python module for "
                f"{sys.executable}; its configure messages above say what is missing "
                "(pybind11, numpy or the Python headers)")
        target = Path(self.get_ext_fullpath(ext.name))
        target.parent.mkdir(parents=True, exist_ok=True)
        shutil.copyfile(built[0], target)


setup(
    package_dir={"": "python"},
    packages=["geotex"],
    ext_modules=[Extension("geotex._geotex", sources=[])],
    cmdclass={"build_ext": CMakeBuild},
    options={"build": {"build_base": "build-pip"}},
)
