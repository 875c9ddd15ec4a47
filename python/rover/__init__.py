"""Dynamics of wheeled planetary rovers on rough terrain, from Python.

>>> import rover
>>> r = rover.simulate(rover.load("swing4"), "scenarios/fig13_slip_rough.toml")
>>> r.status, r.trajectory["X"][-1]

The runs are the command line's (`rover simulate`): the same numbers bit
for bit, the same messages in the exceptions (`RoverError`). Units are SI
(m, s, rad, N, N·m), as in the CSV columns. `Simulation` is a run stepped
by the caller, `rover.gym` a Gymnasium environment over it, `sweep` a
parameter sweep on Ray. `wheel_test` is the single-wheel testbed (`rover
wheel-test`) on soft soil. `estimate` runs the model-based filter and dead
reckoning over a run's sensor log (`rover estimate`). Guide:
docs/PYTHON.md.
"""

from __future__ import annotations

import importlib
import json
import os
from contextlib import contextmanager
from pathlib import Path
from typing import Any, Mapping, Optional, Union

import numpy as np

from . import _native
from ._native import Rover, RoverError, RunFailed, Snapshot
from ._toml import dumps as _toml_dumps

__all__ = [
    "EstimateResult",
    "Result",
    "Rover",
    "RoverError",
    "RunFailed",
    "Simulation",
    "Snapshot",
    "builtins",
    "estimate",
    "load",
    "simulate",
    "sweep",
    "sweep_plan",
    "wheel_test",
]

ScenarioLike = Union[str, os.PathLike, Mapping[str, Any]]
RoverLike = Union[Rover, str, os.PathLike, Mapping[str, Any]]
SoilLike = Union[str, os.PathLike, Mapping[str, Any]]

#: The optional dependencies: module -> the extra of the package that
#: installs it (python/pyproject.toml).
_EXTRAS = {"gymnasium": "gym", "ray": "sweep", "pyarrow": "sweep", "pandas": "pandas"}


def _require(module: str, needed_by: str):
    """Import `module`, or raise ImportError naming the extra that
    installs it (before the caller has done anything)."""
    try:
        return importlib.import_module(module)
    except ImportError as e:
        extra = _EXTRAS.get(module, module)
        raise ImportError(
            f"{needed_by} needs {module}, which is not installed: install the package with its"
            f" `{extra}` extra (from the repository: pip install './python[{extra}]'), or pip install {module}",
            name=module,
        ) from e


def builtins() -> list[str]:
    """The built-in rovers' names."""
    return list(_native.builtins())


def load(source: RoverLike) -> Rover:
    """A rover: a built-in name (``"swing4"``), a description file, a
    description's TOML text, or a dict of the description (as its TOML
    file's tables). A ``pathlib.Path`` (any ``os.PathLike``) is always a
    file; a ``str`` is a file when one of that name exists, else TOML text
    when it holds a line break, else a name or a path. A loaded rover is
    returned as is."""
    if isinstance(source, Rover):
        return source
    if isinstance(source, Mapping):
        return _native.load(_toml_dumps(source), True, "<dict>")
    if isinstance(source, os.PathLike):
        return _native.load(os.fspath(source), False)
    if isinstance(source, str):
        return _native.load(source, False if os.path.isfile(source) else None)
    raise TypeError(
        f"rover: a built-in name, a path, TOML text or a dict is a rover, not {type(source).__name__}"
    )


def _rover_and_scenario(rover, scenario, call: str) -> tuple[Optional[Rover], ScenarioLike]:
    """The loaded rover (None: the scenario's own) and the scenario of a
    call given ``(rover, scenario)``, or the scenario alone (first, or as
    ``scenario=``) when it names its rover."""
    if scenario is None:
        if rover is None:
            raise TypeError(
                f"{call}() needs a scenario: {call}(scenario) when the scenario names its rover"
                f" (`rover = \"swing4\"`), else {call}(rover, scenario)"
            )
        if isinstance(rover, Rover) or (isinstance(rover, str) and rover in _native.builtins()):
            raise TypeError(f"{call}(): a rover but no scenario; give one: {call}(rover, scenario)")
        rover, scenario = None, rover
    return (None if rover is None else load(rover)), scenario


@contextmanager
def _python_words():
    """A RoverError in the command line's words, in Python's (the rover
    is an argument here, not on the command line)."""
    try:
        yield
    except RoverError as e:
        message = str(e)
        if "give one on the command line" not in message:
            raise
        message = message.replace("give one on the command line", "give one as the `rover` argument", 1)
        raise type(e)(message) from None


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


def _column_table(table) -> dict[str, np.ndarray]:
    """A table as it crosses from the native half, column after column
    (names, bytes, rows), as a dict of numpy arrays by column name (each
    contiguous and writable)."""
    columns, data, rows = table
    values = np.frombuffer(data, dtype=np.float64).reshape(len(columns), rows).copy()
    return dict(zip(columns, values))


class Result:
    """A whole run: ``trajectory`` (numpy arrays by CSV column name),
    ``units`` (each column's unit, by name: "m", "rad", "N", ...),
    ``summary`` (summary.json as a dict) and ``status`` ("completed",
    "failed", "embedded" on a soil, or "interrupted"; a run that stopped
    early keeps what it computed).

    ``sensors`` is the sensor log of a scenario with ``[sensors]`` (what
    ``rover simulate`` writes to sensors.csv): numpy arrays by sensors.csv
    column name (``t``, ``gx`` ... ``az``, ``enc{j}``, ``susp{i}``,
    ``fix_X`` ... ``fix_psi``, ``tau{j}``, ``delta{j}``), one value per
    sensor instant, NaN in a fix's columns where no fix was due; None for
    a scenario without ``[sensors]``. ``rover.estimate`` takes it as is."""

    def __init__(
        self,
        columns: list[str],
        table: np.ndarray,
        summary: dict,
        units: list[str],
        sensors: Optional[dict[str, np.ndarray]] = None,
    ):
        self.columns = columns
        self.units = dict(zip(columns, units))
        self.table = table
        self.trajectory = {c: table[:, i] for i, c in enumerate(columns)}
        self.summary = summary
        self.status = summary.get("status")
        self.sensors = sensors

    @property
    def error(self) -> Optional[str]:
        """Why the run stopped early, or None."""
        return self.summary.get("error")

    def to_pandas(self):
        """The trajectory as a pandas DataFrame (pandas must be installed)."""
        pd = _require("pandas", "Result.to_pandas()")
        return pd.DataFrame(self.table, columns=self.columns)

    def __repr__(self) -> str:
        return f"<rover.Result {self.status}: {len(self.table)} rows, t_end = {self.summary.get('t_end')} s>"


def simulate(
    rover: Optional[RoverLike] = None,
    scenario: Optional[ScenarioLike] = None,
    *,
    generic: bool = False,
    mcap: Optional[Union[str, "os.PathLike[str]"]] = None,
) -> Result:
    """Run ``scenario`` (a path, TOML text or a dict) with ``rover`` (a
    loaded rover, a name, a path, TOML text or a dict; None: the scenario's
    own), as ``rover simulate`` does: ``simulate(rover, scenario)``, or
    ``simulate(scenario)`` for a scenario that names its rover. ``generic``
    runs the interpreted plant even for a built-in rover. Raises RoverError
    for a scenario that cannot run. A scenario with ``[sensors]`` also
    gives its sensor log (``Result.sensors``). With ``mcap`` (a file's
    path), the run is also written there as an MCAP log of Foxglove
    messages, as ``rover simulate --mcap`` writes ``run.mcap``
    (docs/VIEW.md); a path that cannot be written raises RoverError
    before the run starts.

    Ctrl-C (SIGINT, or any signal whose Python handler raises) stops the
    run within one output interval and 50 ms: the handler's exception
    (KeyboardInterrupt) is raised with what was computed attached as its
    ``result`` attribute, a Result of status "interrupted" holding the rows
    up to the stop."""
    rover, scenario = _rover_and_scenario(rover, scenario, "simulate")
    text, origin, base, note = _scenario_source(scenario)
    with _noted(note), _python_words():
        (columns, data, rows), summary, units, sensors, raised = _native.simulate(
            rover, text, origin, base, generic, None if mcap is None else os.fspath(mcap)
        )
    table = np.frombuffer(data, dtype=np.float64).reshape(rows, len(columns))
    log = None if sensors is None else _column_table(sensors)
    result = Result(list(columns), table, json.loads(summary), list(units), log)
    if raised is not None:
        raised.result = result
        raise raised
    return result


class EstimateResult:
    """A sensor log estimated (``rover.estimate``), as ``rover estimate``
    writes it: ``estimate`` (estimate.csv's columns as numpy arrays, by
    name: ``t``, the state ``X`` ... ``dy{m}`` with each wheel's spin
    ``omega{j}`` on a soil, each state entry's 1σ ``sigma_<name>``, the
    wheels' normal loads ``Fn{j}`` and slips ``slip{j}``, with an IMU its
    biases ``bgx`` ... ``baz`` and their 1σ), ``dead_reckoning``
    (dead_reckoning.csv's: ``t`` and the state [x; w]), one value per
    sample estimated, and ``summary`` (estimate.json as a dict: the RMS
    errors of both against the truth, the filter's consistency, its cost).
    ``status`` is "completed", or "failed" with ``error``: the rows before
    the failure are kept."""

    def __init__(self, estimate: dict[str, np.ndarray], dead_reckoning: dict[str, np.ndarray], summary: dict):
        self.estimate = estimate
        self.dead_reckoning = dead_reckoning
        self.summary = summary
        self.status = summary.get("status")

    @property
    def error(self) -> Optional[str]:
        """Why the estimation stopped early, or None."""
        return self.summary.get("error")

    def __repr__(self) -> str:
        return (
            f"<rover.EstimateResult {self.status}: {self.summary.get('samples')} samples,"
            f" t_end = {self.summary.get('t_end')} s>"
        )


#: What a sensor log or a truth given as columns holds, for messages.
_LOG_HELP = {
    "sensors": "the sensors.csv columns of the scenario's [sensors], each a 1-D array of one value per sensor"
    " instant (NaN in a fix's columns where no fix is due), as rover.simulate(...).sensors gives them",
    "truth": "the run's columns as run.csv names them, each a 1-D array of one value per row,"
    " as rover.simulate(...).trajectory gives them",
}


def _log_argument(log: Any, table: str) -> Union[str, list[tuple[str, np.ndarray]]]:
    """A sensor log or a truth given as a path (a str, as the native half
    takes it) or as columns (a mapping or a pandas DataFrame: each column
    a C-contiguous 1-D float64 array). A column that is not one is a
    RoverError naming it; anything else a TypeError."""
    if isinstance(log, (str, os.PathLike)):
        return os.fspath(log)
    if not isinstance(log, Mapping) and hasattr(log, "columns") and hasattr(log, "to_numpy"):
        log = {c: log[c].to_numpy() for c in log.columns}  # a pandas DataFrame
    if not isinstance(log, Mapping):
        raise TypeError(
            f"{table}: a path or a mapping of column name to array (or a pandas DataFrame),"
            f" not {type(log).__name__}"
        )
    hint = _LOG_HELP[table]
    columns = []
    for name, values in log.items():
        if not isinstance(name, str):
            raise RoverError(f"error: {table}: the column name {name!r} is not a str\n  = help: {hint}")
        try:
            v = np.asarray(values, dtype=np.float64)
        except (TypeError, ValueError) as e:
            raise RoverError(
                f'error: {table}["{name}"]: not numbers: {e}\n  = help: {hint}'
            ) from None
        if v.ndim != 1:
            raise RoverError(
                f'error: {table}["{name}"]: an array of shape {v.shape}, not one value per instant\n  = help: {hint}'
            )
        columns.append((name, np.ascontiguousarray(v)))
    return columns


def estimate(
    scenario: ScenarioLike,
    sensors: Any,
    truth: Any = None,
    rover: Optional[RoverLike] = None,
    map: str = "true",
    smooth_cutoff: float = 1.0,
    generic: bool = False,
) -> EstimateResult:
    """Estimate a run's sensor log as ``rover estimate`` does: the
    model-based filter (the scenario's rover as its process model, the
    logged commands as its inputs) and dead reckoning, over every sample,
    measured against ``truth`` when given. The same numbers as the command
    line's, bit for bit.

    ``scenario`` is the scenario whose run wrote the log (a path, TOML text
    or a dict): its ``[sensors]`` says what the log holds, its terrain is
    the filter's map. ``rover`` overrides its rover.

    ``sensors`` is the log: a mapping of sensors.csv column name to a 1-D
    array (exactly the columns of the scenario's ``[sensors]``, one value
    per sensor instant, NaN in a fix's columns where no fix is due), as
    ``rover.simulate(...).sensors`` gives it (a simulate ``Result`` is taken
    for its ``sensors``); or a sensors.csv path.

    ``truth`` is what to measure against: a simulate ``Result`` (its
    trajectory), a mapping of run.csv column name to array, or a run.csv
    path; None measures nothing (a path to the log does not bring the
    run.csv beside it, as on the command line).

    ``map`` is "true" (the scenario's terrain) or "smoothed" (features
    shorter than ``smooth_cutoff`` metres removed, as an orbital map would
    give it). ``generic`` runs the interpreted plant even for a built-in
    rover.

    Raises RoverError for a scenario that cannot run or declares no
    ``[sensors]``, and for a log or a truth that does not fit it, naming
    the column and the element (``sensors["gx"][12]``), or the file and
    line, with what is wrong and how to fix it: a column missing or not of
    the declaration, columns of different lengths, a reading not finite,
    times not at the sensors' rate. An estimation that fails on the way
    returns with status "failed" and the rows before."""
    if map not in ("true", "smoothed"):
        raise ValueError(
            f'map: expected "true" (the scenario\'s terrain) or "smoothed" (features shorter than'
            f" smooth_cutoff removed), got {map!r}"
        )
    smoothed = None
    if map == "smoothed":
        smoothed = float(smooth_cutoff)
        if not (np.isfinite(smoothed) and smoothed > 0.0):
            raise ValueError(
                f"smooth_cutoff: the shortest wavelength the smoothed map keeps must be > 0 m, got {smooth_cutoff}"
            )
    if isinstance(sensors, Result):
        if sensors.sensors is None:
            raise RoverError(
                "error: sensors: the run has no sensor log: its scenario declares no [sensors]\n"
                "  = help: simulate a scenario with [sensors] and give its result, or its .sensors"
            )
        sensors = sensors.sensors
    if isinstance(truth, Result):
        truth = truth.trajectory
    log = _log_argument(sensors, "sensors")
    truth = None if truth is None else _log_argument(truth, "truth")
    rover = None if rover is None else load(rover)
    text, origin, base, note = _scenario_source(scenario)
    with _noted(note), _python_words():
        est, dr, summary = _native.estimate(rover, text, origin, base, log, truth, smoothed, generic)
    return EstimateResult(_column_table(est), _column_table(dr), json.loads(summary))


def _float64_vector(values: Any, what: str, lengths: tuple[int, ...], hint: str) -> np.ndarray:
    """`values` (a sequence of numbers or an array convertible to float64)
    as a C-contiguous 1-D float64 array of one of `lengths` values (no
    copy when it is one already); else an error naming `what`, what it
    takes (`hint`) and what it was given."""
    expected = " or ".join(f"{n} values (shape ({n},))" for n in lengths)
    try:
        if values is None or isinstance(values, (str, bytes)):
            raise TypeError("not numbers")
        v = np.asarray(values, dtype=np.float64, order="C")
    except (TypeError, ValueError) as e:
        raise TypeError(
            f"{what}: expected a sequence of numbers or a numeric array of {expected}, {hint};"
            f" got {type(values).__name__} ({e})"
        ) from None
    if v.ndim != 1 or v.shape[0] not in lengths:
        shape = f"({v.shape[0]},)" if v.ndim == 1 else f"({', '.join(map(str, v.shape))})"
        raise ValueError(f"{what}: expected {expected}, {hint}; got shape {shape}")
    return v


class Simulation(_native.Simulation):
    """A scenario run step by step: ``Simulation(rover, scenario)``, or
    ``Simulation(scenario)`` for a scenario that names its rover.

    ``step(n)`` advances n output intervals (``dt`` = 1 / output_rate);
    ``state`` is [x; w] as numpy (2N values: the trajectory's columns after
    ``t``), ``get_state()``/``set_state()`` the full state (``state_size``
    values: [x; w], then the run's internal states); ``columns`` and
    ``units`` name the row's values and their units; ``set_torques``/
    ``set_steering`` take one value per wheel (a list, a tuple or any
    numeric array); ``set_speed``/``set_steering_setpoint`` move the
    built-in loops' set-points. Stepped without changes, the states are the
    whole run's rows bit for bit. Long ``step(n)`` calls release the GIL.

    ``snapshot()`` takes the run's complete condition, ``restore(snap)``
    puts it back: the run then continues bit for bit as it did after the
    snapshot. ``copy.copy``/``copy.deepcopy`` give an independent run in
    the same condition; ``pickle`` keeps the setup and replays the calls
    that led to the current condition (the same numbers, at the cost of
    computing them again).

    Ctrl-C stops a long ``step(n)`` after the step in progress (checked
    every 50 ms): KeyboardInterrupt is raised, and the simulation stays at
    the last step completed (``time``, ``state`` and ``row`` agree), ready
    to step on.
    """

    def __new__(cls, rover=None, scenario=None, *, generic: bool = False, _setup=None):
        if _setup is not None:
            rover, text, origin, base = _setup
            note = None
        else:
            rover, scenario = _rover_and_scenario(rover, scenario, "Simulation")
            text, origin, base, note = _scenario_source(scenario)
        with _noted(note), _python_words():
            self = super().__new__(cls, rover, text, origin, base, generic)
        self._setup = (rover, text, origin, base)
        self._generic = generic
        return self

    def __init__(self, rover=None, scenario=None, *, generic: bool = False, _setup=None):
        self._state = np.empty(2 * self.dof)
        self._row = np.empty(len(self.columns))

    # -- commands from any sequence of numbers ----------------------------

    def set_torques(self, torques) -> None:
        """Open-loop motor torques [N·m], one per wheel (a list, a tuple or
        any numeric array), added to the controller's and held until
        changed."""
        v = _float64_vector(torques, "torques", (self.wheel_count,), "one torque [N·m] per wheel")
        super().set_torques(v)

    def set_steering(self, angles) -> None:
        """Open-loop steering angles [rad], one per wheel (a list, a tuple
        or any numeric array), added to the controller's and held until
        changed."""
        v = _float64_vector(angles, "steering", (self.wheel_count,), "one angle [rad] per wheel")
        super().set_steering(v)

    def get_state(self) -> np.ndarray:
        """The full state (``state_size`` values: [x; w], then the run's
        internal states), a new array; ``time`` is its time."""
        out = np.empty(self.state_size)
        self.full_state_into(out)
        return out

    def set_state(self, values) -> None:
        """Replace the state at the current time (``time`` is kept): 2N
        values [x; w] (the internal states kept) or ``state_size`` values
        (as ``get_state()`` gives them). The integrator restarts from it.
        Raises RunFailed when the run has failed or cannot be evaluated
        there."""
        v = _float64_vector(
            values,
            "state",
            (2 * self.dof, self.state_size),
            f"[x; w] of 2N = {2 * self.dof} values, or the full state of {self.state_size}",
        )
        super().set_state(v)

    def restore(self, snapshot: Snapshot) -> None:
        """Put back a snapshot taken of this simulation (or of one of the
        same rover and scenario): stepped on, the run gives what it gave
        after the snapshot, bit for bit."""
        if not isinstance(snapshot, Snapshot):
            raise TypeError(f"snapshot: expected a Snapshot (from snapshot()), got {type(snapshot).__name__}")
        super().restore(snapshot)

    # -- copies and pickling ---------------------------------------------

    def __copy__(self) -> "Simulation":
        new = type(self).__new__(type(self), generic=self._generic, _setup=self._setup)
        new.__init__()
        new.restore(self.snapshot())
        return new

    def __deepcopy__(self, memo) -> "Simulation":
        new = self.__copy__()
        memo[id(self)] = new
        return new

    def __reduce__(self):
        return (_rebuild_simulation, (type(self), self._setup, self._generic, self.calls()))

    @property
    def state(self) -> np.ndarray:
        """The state [x; w] (a new array each call; ``state_into`` fills
        one). Set it to move the rover (the internal states kept)."""
        out = np.empty(2 * self.dof)
        self.state_into(out)
        return out

    @state.setter
    def state(self, values) -> None:
        v = _float64_vector(values, "state", (2 * self.dof,), f"[x; w] of 2N = {2 * self.dof} values")
        self.set_state(v)

    @property
    def row(self) -> dict:
        """The current trajectory row, by column name."""
        self.row_into(self._row)
        return dict(zip(self.columns, self._row.tolist()))


def _rebuild_simulation(cls, setup, generic, log):
    """An unpickled Simulation: set up again, then the logged calls
    replayed (a failed step fails again, as it did)."""
    sim = cls.__new__(cls, generic=generic, _setup=setup)
    sim.__init__()
    for method, args in log:
        try:
            if method == "step":
                sim.step(int(args[0]))
            elif method in ("set_speed", "set_steering_setpoint"):
                getattr(sim, method)(args[0])
            else:
                getattr(sim, method)(np.array(args))
        except RunFailed:
            pass  # failed as the original did
    return sim


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
