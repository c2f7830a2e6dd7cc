"""The suite runs from the repository root's checkout: linkbox from python/, _linkbox from the
build (PYTHONPATH, set by ctest), and the CLI named by LINKBOX_CLI for comparisons."""
import os
import pathlib

import matplotlib
import pytest

matplotlib.use("Agg")

ROOT = pathlib.Path(__file__).resolve().parents[2]


@pytest.fixture
def cli() -> str:
    path = os.environ.get("LINKBOX_CLI", str(ROOT / "build" / "linkbox"))
    if not os.access(path, os.X_OK):
        pytest.skip("no linkbox executable at " + path + " (set LINKBOX_CLI)")
    return path
