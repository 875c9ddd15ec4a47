"""Dynamics of wheeled planetary rovers on rough terrain, from Python.

>>> import rover
>>> r = rover.simulate(rover.load("swing4"), "scenarios/fig13_slip_rough.toml")
>>> r.status, r.trajectory["X"][-1]

The runs are the command line's (`rover simulate`): the same numbers bit
for bit, the same messages in the exceptions (`RoverError`). Units are SI
(m, s, rad, N, N·m), as in the CSV columns. `wheel_test` is the
single-wheel testbed (`rover wheel-test`) on soft soil.
"""

from __future__ import annotations

import json
import os
from contextlib import contextmanager
from pathlib import Path
from typing import Any, Mapping, Optional, Union

import numpy as np

from . import _native
from ._native import Rover, RoverError, RunFailed
from ._toml import dumps as _toml_dumps

__all__ = [
    "Result",
    "Rover",
    "RoverError",
    "RunFailed",
    "Simulation",
    "builtins",
    "load",
    "simulate",
    "sweep",
    "sweep_plan",
    "wheel_test",
]

ScenarioLike = Union[str, os.PathLike, Mapping[str, Any]]
SoilLike = Union[str, os.PathLike, Mapping[str, Any]]


def builtins() -> list[str]:
    """The built-in rovers' names."""
    return list(_native.builtins())


def load(source: Union[str, os.PathLike]) -> Rover:
    """A rover: a built-in name (``"swing4"``), a description file, or a
    description's TOML text. A ``pathlib.Path`` (any ``os.PathLike``) is
    always a file; a ``str`` is a file when one of that name exists, else
    TOML text when it holds a line break, else a name or a path."""
    if isinstance(source, os.PathLike):
        return _native.load(os.fspath(source), False)
    if isinstance(source, str):
        return _native.load(source, False if os.path.isfile(source) else None)
    raise TypeError(f"a rover is a name, a path or TOML text, not {type(source).__name__}")


def _scenario_source(scenario: ScenarioLike) -> tuple[str, str, str, Optional[str]]:
    """(TOML text, name in messages, folder of relative paths, how a str
    was taken when that can be doubted) of a scenario given as a path, TOML
    text or a dict.

    A ``pathlib.Path`` (any ``os.PathLike``) is always a file. A ``str`` is
    a file when a file of that name exists; else TOML text when it holds a
    line break, or an ``=`` and does not end in ``.toml``; else a path."""
    if isinstance(scenario, Mapping):
        return _toml_dumps(scenario), "<dict>", os.getcwd(), None
    if isinstance(scenario, os.PathLike):
        return (*_read_scenario(Path(scenario), None), None)
    if not isinstance(scenario, str):
        raise TypeError(f"a scenario is a path, TOML text or a dict, not {type(scenario).__name__}")
    if os.path.isfile(scenario):
        return (*_read_scenario(Path(scenario), None), None)
    if "\n" in scenario:
        return scenario, "<string>", os.getcwd(), None
    if "=" in scenario and not scenario.rstrip().endswith(".toml"):
        why = (
            "the scenario string was taken as TOML text: it holds `=` and no file of that name exists"
            " (for a file, give its path as pathlib.Path)"
        )
        return scenario, "<string>", os.getcwd(), why
    why = (
        "the scenario string was taken as a path: it holds no line break"
        + (" and ends in .toml" if "=" in scenario else " and no `=`, as TOML text would")
    )
    return (*_read_scenario(Path(scenario), why), None)


def _read_scenario(path: Path, why: Optional[str]) -> tuple[str, str, str]:
    """A scenario file's text, name and folder; `why` says, in an error,
    why a str was taken as a path."""
    try:
        text = path.read_text()
    except (OSError, UnicodeDecodeError) as e:
        reason = e.strerror if isinstance(e, OSError) and e.strerror else str(e)
        note = f"\n  = note: {why}" if why else ""
        raise RoverError(f"error: {path}: cannot read the scenario file: {reason}{note}") from None
    return text, str(path), str(path.parent)


@contextmanager
def _noted(note: Optional[str]):
    """A RoverError raised within, with `note` (how the scenario was
    taken) added to its message."""
    try:
        yield
    except RoverError as e:
        if note is None:
            raise
        raise type(e)(f"{e}\n  = note: {note}") from None


class Result:
    """A whole run: ``trajectory`` (numpy arrays by CSV column name),
    ``units`` (each column's unit, by name: "m", "rad", "N", ...),
    ``summary`` (summary.json as a dict) and ``status`` ("completed",
    "failed", "embedded" on a soil, or "interrupted"; a run that stopped
    early keeps what it computed)."""

    def __init__(self, columns: list[str], table: np.ndarray, summary: dict, units: list[str]):
        self.columns = columns
        self.units = dict(zip(columns, units))
        self.table = table
        self.trajectory = {c: table[:, i] for i, c in enumerate(columns)}
        self.summary = summary
        self.status = summary.get("status")

    @property
    def error(self) -> Optional[str]:
        """Why the run stopped early, or None."""
        return self.summary.get("error")

    def to_pandas(self):
        """The trajectory as a pandas DataFrame (pandas must be installed)."""
        import pandas as pd

        return pd.DataFrame(self.table, columns=self.columns)

    def __repr__(self) -> str:
        return f"<rover.Result {self.status}: {len(self.table)} rows, t_end = {self.summary.get('t_end')} s>"


def simulate(
    rover: Optional[Union[Rover, str]] = None,
    scenario: Optional[ScenarioLike] = None,
    *,
    generic: bool = False,
) -> Result:
    """Run ``scenario`` (a path, TOML text or a dict) with ``rover`` (a
    loaded rover or a name; None: the scenario's own), as ``rover simulate``
    does. ``generic`` runs the interpreted plant even for a built-in rover.
    Raises RoverError for a scenario that cannot run.

    Ctrl-C (SIGINT, or any signal whose Python handler raises) stops the
    run within one output interval and 50 ms: the handler's exception
    (KeyboardInterrupt) is raised with what was computed attached as its
    ``result`` attribute, a Result of status "interrupted" holding the rows
    up to the stop."""
    if scenario is None:
        raise TypeError("simulate() needs a scenario")
    if isinstance(rover, (str, os.PathLike)):
        rover = load(rover)
    text, origin, base, note = _scenario_source(scenario)
    with _noted(note):
        columns, data, rows, summary, units, raised = _native.simulate(rover, text, origin, base, generic)
    table = np.frombuffer(data, dtype=np.float64).reshape(rows, len(columns))
    result = Result(list(columns), table, json.loads(summary), list(units))
    if raised is not None:
        raised.result = result
        raise raised
    return result


class Simulation(_native.Simulation):
    """A scenario run step by step.

    ``step(n)`` advances n output intervals (``dt`` = 1 / output_rate);
    ``state`` is [x; w] as numpy (2N values: the trajectory's columns after
    ``t``); ``columns`` and ``units`` name the row's values and their units;
    ``set_torques``/``set_steering`` take a numpy float64 array, one
    value per wheel; ``set_speed``/``set_steering_setpoint`` move the
    built-in loops' set-points. Stepped without changes, the states are the
    whole run's rows bit for bit. Long ``step(n)`` calls release the GIL.

    Ctrl-C stops a long ``step(n)`` after the step in progress (checked
    every 50 ms): KeyboardInterrupt is raised, and the simulation stays at
    the last step completed (``time``, ``state`` and ``row`` agree), ready
    to step on.
    """

    def __new__(cls, rover=None, scenario=None, *, generic: bool = False):
        if scenario is None:
            raise TypeError("Simulation() needs a scenario")
        if isinstance(rover, (str, os.PathLike)):
            rover = load(rover)
        text, origin, base, note = _scenario_source(scenario)
        with _noted(note):
            return super().__new__(cls, rover, text, origin, base, generic)

    def __init__(self, rover=None, scenario=None, *, generic: bool = False):
        self._state = np.empty(2 * self.dof)
        self._row = np.empty(len(self.columns))

    @property
    def state(self) -> np.ndarray:
        """The state [x; w] (a new array each call; ``state_into`` fills one)."""
        out = np.empty(2 * self.dof)
        self.state_into(out)
        return out

    @property
    def row(self) -> dict:
        """The current trajectory row, by column name."""
        self.row_into(self._row)
        return dict(zip(self.columns, self._row.tolist()))


def wheel_test(
    soil: SoilLike,
    radius: float,
    width: float,
    load: float,
    slips: Any,
    slip_angle_deg: float = 0.0,
) -> dict[str, np.ndarray]:
    """The single-wheel testbed, as ``rover wheel-test`` runs it: the
    steady state of a rigid wheel (``radius``, ``width`` [m]) carrying
    ``load`` [N] on ``soil`` at each of ``slips`` (each in (-1, 1):
    positive driving, negative braking), under ``slip_angle_deg`` [°].

    ``soil`` is a built-in soil's name (``"lete_sand"``, ``"dry_sand"``,
    ``"lunar_nominal"``, ``"lunar_simulant"``, ``"mars_simulant"``), a TOML
    file with a ``[soil]`` table, or a dict of that table's keys (``n``,
    ``k_c``, ``k_phi``, ``cohesion``, ``friction_angle_deg``,
    ``shear_modulus``; optional ``lateral_shear_modulus``, ``a0``, ``a1``,
    ``rear_ratio``), checked as the file is.

    Returns numpy float64 arrays, one value per slip, by the command line's
    CSV column: ``slip``, ``sinkage`` [m], ``drawbar_pull`` [N], ``torque``
    [N·m], ``lateral_force`` [N], ``entry_angle`` [rad],
    ``drawbar_pull_over_load`` (DP/W) and ``torque_over_load_radius``
    (T/(W·r)); the same numbers bit for bit. Input the command line
    refuses (an unknown soil, a soil key or value outside physics, a slip
    outside (-1, 1), a load the soil cannot carry under the wheel) raises
    ValueError with its message, naming the flag or the ``[soil]`` key."""
    if isinstance(soil, Mapping):
        label, text = "<dict>", _toml_dumps({"soil": soil})
    elif isinstance(soil, (str, os.PathLike)):
        label, text = os.fspath(soil), None
    else:
        raise TypeError(f"a soil is a name, a path or a dict, not {type(soil).__name__}")
    s = np.asarray(slips, dtype=np.float64)
    if s.ndim > 1:
        raise ValueError(f"slips: expected one slip or a 1-D sequence of them, got shape {s.shape}")
    s = np.atleast_1d(s)
    columns, data = _native.wheel_test(label, text, radius, width, load, s.tolist(), slip_angle_deg)
    table = np.frombuffer(data, dtype=np.float64).reshape(len(columns), len(s)).copy()
    return dict(zip(columns, table))


from .sweep import sweep, sweep_plan  # noqa: E402
