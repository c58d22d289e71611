"""Builds the legwork Python package with CMake: configures this source tree
with -DLEGWORK_PYTHON=ON (no tests, benchmarks or fuzzers), builds the
_legwork target and puts the extension next to python/legwork/*.py.

Environment: LEGWORK_CMAKE_ARGS adds CMake arguments; LEGWORK_BUILD_DIR sets
the CMake build directory (default build/pip-<python>); CMAKE_BUILD_PARALLEL_LEVEL
the jobs."""
import os
import shlex
import shutil
import subprocess
import sys
import sysconfig

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

ROOT = os.path.dirname(os.path.abspath(__file__))


class CMakeBuild(build_ext):
    def build_extension(self, ext):
        tag = sysconfig.get_config_var("SOABI") or "py"
        build = os.environ.get("LEGWORK_BUILD_DIR", os.path.join(ROOT, "build", "pip-" + tag))
        args = [
            "-DCMAKE_BUILD_TYPE=Release",
            "-DLEGWORK_PYTHON=ON",
            "-DLEGWORK_TESTS=OFF",
            "-DLEGWORK_BENCH=OFF",
            "-DLEGWORK_FUZZ=OFF",
            "-DPython_EXECUTABLE=" + sys.executable,
        ]
        if shutil.which("ninja"):
            args.append("-GNinja")
        if shutil.which("ccache"):
            args += ["-DCMAKE_CXX_COMPILER_LAUNCHER=ccache", "-DCMAKE_C_COMPILER_LAUNCHER=ccache"]
        args += shlex.split(os.environ.get("LEGWORK_CMAKE_ARGS", ""))
        subprocess.check_call(["cmake", "-S", ROOT, "-B", build, *args])
        subprocess.check_call(["cmake", "--build", build, "--target", "_legwork"])
        built = os.path.join(build, "python", "legwork", os.path.basename(self.get_ext_filename(ext.name)))
        if not os.path.exists(built):
            raise RuntimeError(f"CMake did not produce {built}: are pybind11 (python3-pybind11) and python3-dev installed?")
        target = self.get_ext_fullpath(ext.name)
        os.makedirs(os.path.dirname(target), exist_ok=True)
        shutil.copyfile(built, target)


setup(
    packages=["legwork"],
    package_dir={"legwork": "python/legwork"},
    ext_modules=[Extension("legwork._legwork", sources=[])],
    cmdclass={"build_ext": CMakeBuild},
    zip_safe=False,
)
