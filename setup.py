"""Builds the Python module ontogen: CMake builds the extension ontogen._ontogen with the
libraries (-DONTOGEN_PYTHON=ON, without tests, benchmarks or the executable), setuptools
installs it beside the package's Python files (python/ontogen/). CMAKE_ARGS adds CMake
options; CMAKE_BUILD_PARALLEL_LEVEL sets the jobs (default: every core)."""

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
        build = pathlib.Path(self.build_temp).resolve() / "cmake"
        configure = [
            "cmake", "-S", str(ROOT), "-B", str(build), "-DCMAKE_BUILD_TYPE=Release",
            "-DONTOGEN_PYTHON=ON", f"-DPython_EXECUTABLE={sys.executable}",
            "-DONTOGEN_BUILD_TESTS=OFF", "-DONTOGEN_BUILD_BENCH=OFF", "-DONTOGEN_INSTALL=OFF",
            "-DONTOGEN_LIVE_MIDI=OFF", "-DONTOGEN_MPI=OFF",
            *shlex.split(os.environ.get("CMAKE_ARGS", "")),
        ]
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
