"""Builds the `sonarsim` extension module with the project's CMake (target sonarsim_python) and installs it.

pip runs this through pyproject.toml. The build needs what .ci/setup.sh installs (a C++ compiler, CMake, Ninja,
Embree, OpenMesh, TBB, pybind11 ...); it downloads nothing. Environment:
  SONARSIM_PIP_BUILD_DIR  CMake build directory to use (default: setuptools' temporary build directory)
  SONARSIM_CMAKE_ARGS     extra CMake arguments, split on spaces
"""
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
    """Configures the whole project without tests or viewer and builds only the Python module's target."""

    def build_extension(self, ext):
        target = pathlib.Path(self.get_ext_fullpath(ext.name)).resolve()
        build_dir = pathlib.Path(os.environ.get("SONARSIM_PIP_BUILD_DIR") or pathlib.Path(self.build_temp) / "cmake")
        build_dir = build_dir.resolve()
        build_dir.mkdir(parents=True, exist_ok=True)
        configure = [
            "cmake", "-S", str(ROOT), "-B", str(build_dir), "-DCMAKE_BUILD_TYPE=Release",
            "-DSONARSIM_BUILD_TESTS=OFF", "-DSONARSIM_BUILD_VIEWER=OFF", "-DSONARSIM_BUILD_PYTHON=ON",
            f"-DPython3_EXECUTABLE={sys.executable}",
        ]
        if shutil.which("ninja"):
            configure += ["-G", "Ninja"]
        configure += os.environ.get("SONARSIM_CMAKE_ARGS", "").split()
        jobs = str(os.cpu_count() or 1)
        print(f"sonarsim: building the module with CMake in {build_dir}", flush=True)
        subprocess.run(configure, check=True)
        subprocess.run(["cmake", "--build", str(build_dir), "--target", "sonarsim_python", "-j", jobs], check=True)
        built = sorted((build_dir / "python").glob("sonarsim*.so"))
        if len(built) != 1:
            raise RuntimeError(f"expected one sonarsim*.so in {build_dir / 'python'}, found {built}")
        target.parent.mkdir(parents=True, exist_ok=True)
        shutil.copyfile(built[0], target)


setup(ext_modules=[CMakeExtension("sonarsim")], cmdclass={"build_ext": CMakeBuild}, zip_safe=False)
