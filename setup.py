"""setuptools glue for pyproject.toml: the extension is built by CMake, not by setuptools.

`pip install .` configures a CMake build of the target _rtlacam (Release, no apps' tests)
in build/pip (or in $RTLACAM_BUILD_DIR, an existing build tree, which makes a reinstall
cheap) and copies the module next to python/rtlacam/*.py in the wheel.
"""
import os
import shutil
import subprocess
import sys
from pathlib import Path

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

ROOT = Path(__file__).resolve().parent


class CMakeExtension(Extension):
    def __init__(self, name):
        super().__init__(name, sources=[])


class CMakeBuild(build_ext):
    def build_extension(self, ext):
        build = Path(os.environ.get("RTLACAM_BUILD_DIR", ROOT / "build" / "pip")).resolve()
        if not (build / "CMakeCache.txt").exists():
            args = ["cmake", "-S", str(ROOT), "-B", str(build), "-DCMAKE_BUILD_TYPE=Release", "-DRTLACAM_PYTHON=ON",
                    "-DRTLACAM_BUILD_TESTS=OFF", "-DRTLACAM_WITH_SUMO=OFF", f"-DPython3_EXECUTABLE={sys.executable}"]
            try:  # pybind11 from pip (an isolated build); Debian's pybind11-dev is found by CMake itself
                import pybind11
                args.append(f"-Dpybind11_DIR={pybind11.get_cmake_dir()}")
            except ImportError:
                pass
            subprocess.run(args, check=True)
        jobs = os.environ.get("CMAKE_BUILD_PARALLEL_LEVEL", str(os.cpu_count() or 2))
        subprocess.run(["cmake", "--build", str(build), "--target", "_rtlacam", "-j", jobs], check=True)
        built = list((build / "python" / "rtlacam").glob("_rtlacam*.so"))
        if not built:
            sys.exit(f"rtlacam: no _rtlacam*.so in {build}/python/rtlacam after the CMake build")
        dest = Path(self.get_ext_fullpath(ext.name))
        dest.parent.mkdir(parents=True, exist_ok=True)
        shutil.copy2(built[0], dest)


setup(
    ext_modules=[CMakeExtension("rtlacam._rtlacam")],
    cmdclass={"build_ext": CMakeBuild},
    # setuptools' own staging, out of the way of a CMake tree in build/ (ignored by git)
    options={"build": {"build_base": str(Path("build") / "pip-setuptools")}},
)
