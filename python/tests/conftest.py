"""Shared fixtures: the command line to compare with, the tests' data."""

import os
import shutil
import subprocess
from pathlib import Path

import pytest

DATA = Path(__file__).parent / "data"
REPO = Path(__file__).resolve().parents[2]


def cli_path() -> str:
    """The `rover` executable: $ROVER_CLI, else the one cargo built."""
    exe = os.environ.get("ROVER_CLI")
    if exe:
        return exe
    target = Path(os.environ.get("CARGO_TARGET_DIR", REPO / "target"))
    for profile in ("release", "debug"):
        p = target / profile / "rover"
        if p.exists():
            return str(p)
    found = shutil.which("rover")
    if found:
        return found
    pytest.fail("no `rover` executable: build it (cargo build -p rover) or set ROVER_CLI")


@pytest.fixture(scope="session")
def cli():
    exe = cli_path()

    def run(*args, check=True):
        return subprocess.run([exe, *map(str, args)], capture_output=True, text=True, check=check)

    return run


@pytest.fixture
def data():
    return DATA
