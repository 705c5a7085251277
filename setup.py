"""Builds the Python module with the project's own CMake (target _hdimesh) for pip.

    python3 -m venv --system-site-packages V && V/bin/pip install --no-build-isolation .

HDIMESH_BUILD_BASE moves setuptools' build folder (default build/ in the source tree, which
.gitignore covers); the CMake tree lives in its temp folder, so a rerun rebuilds incrementally.
"""
import glob
import os
import re
import shutil
import subprocess
import sys

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

SOURCE_DIR = os.path.dirname(os.path.abspath(__file__))
BUILD_BASE = os.environ.get("HDIMESH_BUILD_BASE", "build")


def project_version():
    with open(os.path.join(SOURCE_DIR, "CMakeLists.txt")) as f:
        return re.search(r"project\(hdimesh\s+VERSION\s+([0-9.]+)", f.read()).group(1)


class CMakeBuild(build_ext):
    def build_extension(self, ext):
        cmake_dir = os.path.abspath(os.path.join(self.build_temp, "cmake"))
        # this interpreter (a venv's): the top CMakeLists.txt takes /usr/bin/python3 otherwise
        configure = [
            "cmake", "-S", SOURCE_DIR, "-B", cmake_dir,
            "-DCMAKE_BUILD_TYPE=Release", "-DCMAKE_UNITY_BUILD=ON",
            "-DHDIMESH_BUILD_PYTHON=ON", "-DHDIMESH_BUILD_TESTS=OFF",
            "-DHDIMESH_BUILD_APPS=OFF", "-DHDIMESH_BUILD_BENCH=OFF",
            "-DPython3_EXECUTABLE=" + sys.executable,
        ]
        subprocess.check_call(configure)
        jobs = os.environ.get("CMAKE_BUILD_PARALLEL_LEVEL") or str(os.cpu_count() or 1)
        build = ["cmake", "--build", cmake_dir, "--target", "_hdimesh", "-j", jobs]
        if subprocess.call(build) != 0:
            # without pybind11-dev or python3-dev CMake skips python/ and has no such target
            sys.exit("hdimesh: building _hdimesh failed; scripts/install_deps.sh installs "
                     "what it needs (pybind11-dev, python3-dev, ...)")
        built = glob.glob(os.path.join(cmake_dir, "python", "hdimesh", "_hdimesh*.so"))
        if len(built) != 1:
            sys.exit("hdimesh: expected one _hdimesh*.so in %s, found %s" % (cmake_dir, built))
        target = self.get_ext_fullpath(ext.name)
        os.makedirs(os.path.dirname(target), exist_ok=True)
        shutil.copyfile(built[0], target)


# egg_info wants its folder to exist already
os.makedirs(BUILD_BASE, exist_ok=True)
setup(
    version=project_version(),
    packages=["hdimesh"],
    package_dir={"": "python"},
    # no sources: CMake builds it (CMakeBuild), setuptools only names and packs it
    ext_modules=[Extension("hdimesh._hdimesh", sources=[])],
    cmdclass={"build_ext": CMakeBuild},
    # setuptools' scratch (and the egg-info) under one ignored folder, not in python/
    options={"build": {"build_base": BUILD_BASE}, "egg_info": {"egg_base": BUILD_BASE}},
    zip_safe=False,
)
