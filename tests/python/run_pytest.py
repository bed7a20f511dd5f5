"""Runs the Python module's tests with pytest; exits 77 (skipped) when pytest or numpy is
missing, except in CI (CI=true), where a missing checker fails the test."""

import importlib.util
import os
import sys

missing = [name for name in ("pytest", "numpy") if importlib.util.find_spec(name) is None]
if missing:
    print("missing Python packages: " + ", ".join(missing) + " (bash .ci/setup --checkers installs them)")
    sys.exit(1 if os.environ.get("CI") == "true" else 77)

import pytest  # noqa: E402

sys.exit(pytest.main(["-q", "-p", "no:cacheprovider", *sys.argv[1:]]))
