"""Builds the Python module ontogen: CMake builds the extension ontogen._ontogen with the
libraries (-DONTOGEN_PYTHON=ON, without tests, benchmarks or the executable), setuptools
installs it beside the package's Python files (python/ontogen/). CMAKE_ARGS adds CMake
options; CMAKE_BUILD_PARALLEL_LEVEL sets the jobs (default: every core).
ONTOGEN_CMAKE_BUILD_DIR names a CMake build folder of this source already configured with
-DONTOGEN_PYTHON=ON: the module is then built there, up to date or incrementally, and that
folder's configuration is left as it is (CMAKE_ARGS does not apply)."""

import os
import pathlib
import re
import shlex
import shutil
import subprocess
import sys

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

ROOT = pathlib.Path(__file__).resolve().parent


def version():
    return re.search(r"project\(ontogen VERSION ([0-9.]+)", (ROOT / "CMakeLists.txt").read_text()).group(1)


class CMakeBuild(build_ext):
    def build_extension(self, ext):
        target = pathlib.Path(self.get_ext_fullpath(ext.name)).resolve()
        reused = os.environ.get("ONTOGEN_CMAKE_BUILD_DIR")
        build = pathlib.Path(reused).resolve() if reused else pathlib.Path(self.build_temp).resolve() / "cmake"
        if reused:
            self.check_reused(build)
        configure = [
            "cmake", "-S", str(ROOT), "-B", str(build), "-DCMAKE_BUILD_TYPE=Release",
            "-DONTOGEN_PYTHON=ON", f"-DPython_EXECUTABLE={sys.executable}",
            "-DONTOGEN_BUILD_TESTS=OFF", "-DONTOGEN_BUILD_BENCH=OFF", "-DONTOGEN_INSTALL=OFF",
            "-DONTOGEN_LIVE_MIDI=OFF", "-DONTOGEN_MPI=OFF",
            *shlex.split(os.environ.get("CMAKE_ARGS", "")),
        ]
        if not reused:
            subprocess.run(configure, check=True)
        jobs = os.environ.get("CMAKE_BUILD_PARALLEL_LEVEL") or str(os.cpu_count() or 1)
        subprocess.run(["cmake", "--build", str(build), "--target", "ontogen_python", "-j", jobs], check=True)
        built = sorted((build / "python" / "ontogen").glob("_ontogen*" + (".pyd" if os.name == "nt" else ".so")))
        if not built:
            raise RuntimeError(f"the build made no extension in {build / 'python' / 'ontogen'}")
        target.parent.mkdir(parents=True, exist_ok=True)
        shutil.copyfile(built[0], target)
        # The notebook's 3-D viewer, bundled when esbuild and three.js were there.
        viewer = build / "python" / "ontogen" / "viewer.js"
        if viewer.exists():
            shutil.copyfile(viewer, target.parent / "viewer.js")

    @staticmethod
    def check_reused(build):
        """A reused folder must be a build of this version of ontogen with the module on,
        else the module installed would not be the one this source describes."""
        cache = build / "CMakeCache.txt"
        if not cache.is_file():
            raise RuntimeError(f"ONTOGEN_CMAKE_BUILD_DIR={build}: no CMakeCache.txt there")
        entries = dict(re.findall(r"^([A-Za-z_]+):[A-Z]+=(.*)$", cache.read_text(), re.M))
        if entries.get("ONTOGEN_PYTHON", "").upper() not in ("ON", "TRUE", "1", "YES"):
            raise RuntimeError(f"ONTOGEN_CMAKE_BUILD_DIR={build} is configured without -DONTOGEN_PYTHON=ON")
        if entries.get("CMAKE_PROJECT_VERSION") != version():
            raise RuntimeError(f"ONTOGEN_CMAKE_BUILD_DIR={build} builds ontogen "
                               f"{entries.get('CMAKE_PROJECT_VERSION', '(unknown)')}, this source is {version()}")
        print(f"building the module in {build}, a build of {entries.get('CMAKE_HOME_DIRECTORY', '(unknown)')}")


setup(
    name="ontogen",
    version=version(),
    description="Grow, read and draw ontogen's cell-language models from Python",
    python_requires=">=3.9",
    install_requires=["numpy"],
    packages=["ontogen"],
    package_dir={"ontogen": "python/ontogen"},
    ext_modules=[Extension("ontogen._ontogen", sources=[])],
    cmdclass={"build_ext": CMakeBuild},
    zip_safe=False,
)
