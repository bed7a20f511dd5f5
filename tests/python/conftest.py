"""What the tests of the Python module share: the ontogen executable and the source tree
(given by the test's environment), a scratch folder."""

import json
import os
import pathlib
import subprocess

import pytest

SOURCE = pathlib.Path(os.environ.get("ONTOGEN_SOURCE_DIR", pathlib.Path(__file__).resolve().parents[2]))
MODELS = SOURCE / "models"


def executable():
    path = os.environ.get("ONTOGEN_EXECUTABLE")
    if not path:
        pytest.skip("ONTOGEN_EXECUTABLE is not set (ctest sets it)")
    return path


def cli(*args, check=True):
    """Runs the ontogen executable; returns its standard output."""
    done = subprocess.run([executable(), *map(str, args)], capture_output=True, text=True)
    if check and done.returncode != 0:
        raise AssertionError(f"ontogen {' '.join(map(str, args))} failed ({done.returncode}): {done.stderr}")
    return done.stdout


def word_json(path, times, seed):
    """`ontogen word --json` at `times`: the document as Python data."""
    return json.loads(cli("word", path, "--json", "--seed", seed, "--at", ",".join(repr(float(t)) for t in times)))
