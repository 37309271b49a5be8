"""Packages the `tessera` Python module for pip:

    pip install --no-build-isolation ./python

The compiled part (_tessera*.so) is the one the repository's CMake build made
in $TESSERA_BUILD_DIR (default: build/ beside this folder), copied beside the
package's Python files. Where there is none, it is built first with CMake in
build-python/ (Release, the module only), with the Python that runs pip.
"""
import os
import pathlib
import shutil
import subprocess
import sys
import sysconfig

from setuptools import setup
from setuptools.command.build_py import build_py
from setuptools.dist import Distribution

HERE = pathlib.Path(__file__).resolve().parent
REPOSITORY = HERE.parent
MODULE = "_tessera" + sysconfig.get_config_var("EXT_SUFFIX")


def module_in(build_dir):
    path = pathlib.Path(build_dir) / "python" / "tessera" / MODULE
    return path if path.is_file() else None


def built_module():
    given = os.environ.get("TESSERA_BUILD_DIR")
    found = module_in(given or REPOSITORY / "build")
    if found or given:
        if not found:
            sys.exit(f"tessera: error: no {MODULE} in {given}/python/tessera (build the target tessera_python)")
        return found
    build_dir = REPOSITORY / "build-python"
    subprocess.check_call(["cmake", "-S", str(REPOSITORY), "-B", str(build_dir), "-DCMAKE_BUILD_TYPE=Release",
                           "-DTESSERA_BUILD_PYTHON=ON", "-DTESSERA_BUILD_TESTS=OFF",
                           "-DTESSERA_BUILD_GL_REFERENCE=OFF", "-DTESSERA_BUILD_MICROBENCH=OFF",
                           f"-DPython3_EXECUTABLE={sys.executable}"])
    subprocess.check_call(["cmake", "--build", str(build_dir), "--target", "tessera_python",
                           "-j", str(os.cpu_count() or 1)])
    return module_in(build_dir)


class BuildWithModule(build_py):
    def run(self):
        super().run()
        target = pathlib.Path(self.build_lib) / "tessera"
        target.mkdir(parents=True, exist_ok=True)
        shutil.copy2(built_module(), target / MODULE)


class BinaryDistribution(Distribution):
    def has_ext_modules(self):  # a platform wheel: the package holds a compiled module
        return True


setup(cmdclass={"build_py": BuildWithModule}, distclass=BinaryDistribution)
