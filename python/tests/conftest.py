"""Shared fixtures: the command line to compare with, the tests' data."""

import os
import shutil
import signal
import subprocess
import threading
import time
from contextlib import contextmanager
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


#: A run far longer than the tests wait: RK4 at 10 µs computes each
#: simulated second for about half a second (an output interval, 25 ms),
#: whatever the ground does.
LONG = {
    "rover": "swing4",
    "duration": 200.0,
    "output_rate": 20.0,
    "control": {"speed": {"speed": 0.1}},
    "integrator": {"rk4": {"step": 1e-5}},
}


@contextmanager
def interrupt_after(seconds):
    """SIGINT to this process in `seconds`, as Ctrl-C sends it; never
    after the block. Yields a list that holds, once sent, the
    `time.monotonic()` of the signal. Python's own handler is installed
    for the block: a process started with SIGINT ignored (a shell's
    background job) keeps it ignored, and the signal would never arrive."""
    previous = signal.signal(signal.SIGINT, signal.default_int_handler)
    sent = []

    def send():
        sent.append(time.monotonic())
        os.kill(os.getpid(), signal.SIGINT)

    timer = threading.Timer(seconds, send)
    timer.start()
    try:
        yield sent
    finally:
        timer.cancel()
        timer.join()
        signal.signal(signal.SIGINT, previous)
