"""`pip install` as docs/PYTHON.md says it: in a virtual environment made with
`python3 -m venv --system-site-packages V`, `V/bin/pip install --no-build-isolation .` at
the root of a copy of the source tree builds the module through CMake (setup.py) and
installs it; that environment's Python then imports it from the environment and grows
Koch's curve, and its World shows itself in 3-D (the viewer installed beside it).

    run_pip_install.py SOURCE_DIR WORK_DIR STUDIO_MODULES VERSION [BUILD_DIR]

The copy keeps pip's and setuptools' folders (build/, *.egg-info) out of the source tree.
With BUILD_DIR (as ctest runs it: the build the other tests use), setup.py builds the
module there (ONTOGEN_CMAKE_BUILD_DIR), where it is already up to date: the test then costs
seconds and checks everything pip does but the compile. Without it the whole build runs
as a user's does, from nothing (about five minutes on two cores): the compiles go through
ccache where it is installed, with CCACHE_BASEDIR at the copy. --no-index: nothing is
downloaded (numpy, setuptools and wheel come from the system). Exit 0: passed; 1: failed;
77: a checker is missing (a failure when CI=true)."""

import os
import shutil
import subprocess
import sys
import time

source, work, studio_modules, version = sys.argv[1:5]
reused_build = sys.argv[5] if len(sys.argv) > 5 else None
ci = os.environ.get("CI") == "true"


def missing(what):
    print(f"pip install test: {what} is missing (bash .ci/setup installs it)", file=sys.stderr)
    sys.exit(1 if ci else 77)


for module, package in (("venv", "python3-venv"), ("ensurepip", "python3-venv"), ("setuptools", "python3-setuptools"),
                        ("wheel", "python3-wheel"), ("numpy", "python3-numpy")):
    try:
        __import__(module)
    except ImportError:
        missing(package)

started = time.monotonic()
shutil.rmtree(work, ignore_errors=True)
tree = os.path.join(work, "ontogen")
# The tree as a checkout has it: no build folders, no tools, no git.
top_level_skipped = {".git", ".tools", "Testing"}


def ignore(folder, names):
    skipped = {"__pycache__", "node_modules"}
    if os.path.samefile(folder, source):
        skipped |= top_level_skipped | {n for n in names if n.startswith("build")}
    return [n for n in names if n in skipped]


shutil.copytree(source, tree, ignore=ignore, symlinks=True)
venv = os.path.join(work, "V")
subprocess.run([sys.executable, "-m", "venv", "--system-site-packages", venv], check=True)

env = dict(os.environ)
env.update({
    "CMAKE_BUILD_PARALLEL_LEVEL": "2",
    # CMake takes a compiler launcher from the environment; ccache with the copy as its
    # base folder hashes paths relative to it.
    "CCACHE_BASEDIR": tree,
    "CCACHE_NOHASHDIR": "1",
    "CMAKE_ARGS": f"-DONTOGEN_STUDIO_MODULES={studio_modules}",
})
env.pop("PYTHONPATH", None)
if reused_build:
    env["ONTOGEN_CMAKE_BUILD_DIR"] = reused_build
if shutil.which("ccache"):
    env["CMAKE_CXX_COMPILER_LAUNCHER"] = env["CMAKE_C_COMPILER_LAUNCHER"] = "ccache"
pip = [os.path.join(venv, "bin", "pip"), "install", "--no-build-isolation", "--no-index", "."]
print("$ (cd", tree, "&&", " ".join(pip[0:1] + pip[1:]) + ")", flush=True)
installed = subprocess.run(pip, cwd=tree, env=env, capture_output=True, text=True)
built = time.monotonic()
if installed.returncode != 0:
    print(installed.stdout[-6000:] + installed.stderr[-6000:])
    print("FAIL pip install")
    sys.exit(1)
print(f"ok   pip install built and installed ontogen ({built - started:.0f} s with the copy and the venv)")

check = r"""
import os, sys
import numpy as np
import ontogen
venv, version = sys.argv[1:3]
assert os.path.realpath(ontogen.__file__).startswith(os.path.realpath(venv)), ontogen.__file__
assert ontogen.__version__ == version, ontogen.__version__
program = ontogen.compile("lsystem koch {\n  #angle 90\n  axiom F\n  F -> F + F - F - F + F\n}\n")
world = program.world()
world.advance(3)
arrays = world.arrays()
assert len(arrays["id"]) == 249, len(arrays["id"])
assert int(np.sum(arrays["label"] == arrays["labels"].index("F"))) == 125
view = world._repr_html_()
assert view is not None and view.startswith("<iframe srcdoc="), "no 3-D view: the viewer was not installed"
print("koch n = 3:", len(arrays["id"]), "modules from", ontogen.__file__)
"""
# Run from outside the copy, so that only the installed package can be imported.
grown = subprocess.run([os.path.join(venv, "bin", "python"), "-c", check, venv, version], cwd=work, env=env,
                       capture_output=True, text=True)
print(grown.stdout + grown.stderr, end="")
if grown.returncode != 0:
    print("FAIL the installed module")
    sys.exit(1)
print("ok   V/bin/python imports the installed ontogen, grows Koch (249 modules, 125 F) and shows it in 3-D")
print(f"pip install test: {time.monotonic() - started:.0f} s")
