"""The `pip install .` build: setuptools with a build_ext that runs CMake.

The extension `floornav._floornav` is the CMake target `_floornav` (python/CMakeLists.txt): it is
configured for the Python that runs pip (FLOORNAV_BUILD_PYTHON=ON, no tests, benchmarks or
examples), built, and copied into the package. Where:

- by default in `build-pip/cmake` beside this file: a second `pip install .` rebuilds only what
  changed; a compiler launcher (`ccache`) is used when one is on PATH;
- with FLOORNAV_CMAKE_BUILD_DIR set, in that folder: an existing build (the developers' `build/`,
  configured for the same Python) is used as it is, and only `_floornav` is brought up to date;
- CMAKE_ARGS (space-separated) are added to the configure step; CMAKE_BUILD_PARALLEL_LEVEL sets
  the build's jobs.

setuptools rather than scikit-build-core: Debian 12 packages setuptools (python3-setuptools),
not scikit-build-core, and `pip install --no-build-isolation .` must work offline.
"""

import os
import re
import shlex
import shutil
import subprocess
import sys
from pathlib import Path

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

ROOT = Path(__file__).resolve().parent


def cmake_version() -> str:
    text = (ROOT / "CMakeLists.txt").read_text(encoding="utf-8")
    m = re.search(r"project\(floornav\s+VERSION\s+([0-9.]+)", text)
    if not m:
        raise RuntimeError("CMakeLists.txt: no project(floornav VERSION ...)")
    return m.group(1)


class CMakeBuild(build_ext):
    def build_extension(self, ext: Extension) -> None:
        given = os.environ.get("FLOORNAV_CMAKE_BUILD_DIR")
        build = Path(given).resolve() if given else ROOT / "build-pip" / "cmake"
        if not (build / "CMakeCache.txt").exists() or not given:
            self.configure(build)
        jobs = os.environ.get("CMAKE_BUILD_PARALLEL_LEVEL") or str(os.cpu_count() or 2)
        subprocess.run(["cmake", "--build", str(build), "--target", "_floornav", "-j", jobs],
                       check=True)
        built = sorted((build / "python" / "floornav").glob("_floornav*.so"))
        if not built:
            raise RuntimeError(f"{build}: the build made no python/floornav/_floornav*.so")
        target = Path(self.get_ext_fullpath(ext.name))
        target.parent.mkdir(parents=True, exist_ok=True)
        shutil.copyfile(built[0], target)
        # A build with OMPL: the rrt_connect planner's module (built with the extension), which
        # the extension loads from beside itself on the first rrt_connect plan.
        module = build / "libfloornav_rrt_connect.so"
        if module.exists():
            shutil.copyfile(module, target.parent / module.name)

    @staticmethod
    def configure(build: Path) -> None:
        args = ["cmake", "-S", str(ROOT), "-B", str(build), "-DCMAKE_BUILD_TYPE=Release",
                "-DFLOORNAV_BUILD_PYTHON=ON", "-DFLOORNAV_BUILD_TESTS=OFF",
                "-DFLOORNAV_BUILD_BENCH=OFF", "-DFLOORNAV_BUILD_EXAMPLES=OFF",
                "-DFLOORNAV_BUILD_TOOL=OFF",  # the module needs no CLI11 or OpenSSL
                f"-DPython3_EXECUTABLE={sys.executable}"]
        if shutil.which("ninja") and not (build / "CMakeCache.txt").exists():
            args += ["-G", "Ninja"]
        if shutil.which("ccache"):
            args.append("-DCMAKE_CXX_COMPILER_LAUNCHER=ccache")
        args += shlex.split(os.environ.get("CMAKE_ARGS", ""))
        subprocess.run(args, check=True)


setup(
    version=cmake_version(),
    ext_modules=[Extension("floornav._floornav", sources=[])],
    cmdclass={"build_ext": CMakeBuild},
    options={"build": {"build_base": "build-pip/setuptools"}},
    zip_safe=False,
)
