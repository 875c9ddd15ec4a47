"""The native half of the package `rover` (Rust, built by maturin): what
python/rover/ builds its API on. Arrays cross as buffers: a float64 numpy
array in, read or filled in place."""

from typing import Any, Optional, Union

class RoverError(Exception):
    """A rover, scenario or plan that cannot run; the message is the
    command line's, located at the offending file, line and field."""

class RunFailed(RoverError):
    """A step-wise run failed (the integrator gave up, the rover rolled
    over or left the map); reset() starts it again."""

class Rover:
    """A loaded rover: its description, and what it was loaded from."""

    @property
    def name(self) -> str: ...
    @property
    def dof(self) -> int: ...
    @property
    def coordinate_names(self) -> list[str]: ...
    @property
    def wheel_names(self) -> list[str]: ...
    @property
    def max_torque(self) -> list[float]: ...
    @property
    def steerable(self) -> list[bool]: ...
    @property
    def source(self) -> str: ...
    def report(self) -> str: ...
    def __reduce__(self) -> tuple[Any, tuple[str, bool]]: ...

class Snapshot:
    """A step-wise run's complete condition at one instant (opaque), for
    Simulation.restore()."""

    @property
    def time(self) -> float: ...

class Simulation:
    """A scenario run step by step (the package's `rover.Simulation` is
    the class to use)."""

    def __new__(
        cls, rover: Optional[Rover], text: str, origin: str, base: str, generic: bool = False
    ) -> "Simulation": ...
    def reset(self) -> None: ...
    def step(self, n: int = 1) -> float: ...
    @property
    def time(self) -> float: ...
    @property
    def dt(self) -> float: ...
    @property
    def dof(self) -> int: ...
    @property
    def wheel_count(self) -> int: ...
    @property
    def state_size(self) -> int: ...
    @property
    def columns(self) -> list[str]: ...
    @property
    def units(self) -> list[str]: ...
    @property
    def error(self) -> Optional[str]: ...
    def state_into(self, out: Any) -> None: ...
    def full_state_into(self, out: Any) -> None: ...
    def set_state(self, values: Any) -> None: ...
    def row_into(self, out: Any) -> None: ...
    def set_torques(self, torques: Any) -> None: ...
    def set_steering(self, angles: Any) -> None: ...
    def set_speed(self, speed: float) -> None: ...
    def set_steering_setpoint(self, value: float) -> None: ...
    def snapshot(self) -> Snapshot: ...
    def restore(self, snapshot: Snapshot) -> None: ...
    def calls(self) -> list[tuple[str, list[float]]]: ...

#: A table of numbers: its column names, its values as native-endian
#: float64 bytes (row after row for a trajectory, column after column
#: otherwise), its row count.
Table = tuple[list[str], bytes, int]

#: A log handed to `estimate`: a file's path, or (column name, 1-D
#: C-contiguous float64 array) pairs.
Log = Union[str, list[tuple[str, Any]]]

def load(source: str, text: Optional[bool] = None, origin: Optional[str] = None) -> Rover: ...
def simulate(
    rover: Optional[Rover],
    text: str,
    origin: str,
    base: str,
    generic: bool = False,
    mcap: Optional[str] = None,
) -> tuple[Table, str, list[str], Optional[Table], Optional[BaseException]]:
    """A whole run: the trajectory (row after row), the summary as JSON,
    the columns' units, the sensor log of a scenario with [sensors]
    (column after column, NaN where no fix was due) and the exception a
    signal handler raised, which stopped the run. With `mcap`, the run's
    MCAP log is written to that path."""

def estimate(
    rover: Optional[Rover],
    text: str,
    origin: str,
    base: str,
    sensors: Log,
    truth: Optional[Log] = None,
    smoothed: Optional[float] = None,
    generic: bool = False,
) -> tuple[Table, Table, str]:
    """A sensor log estimated as `rover estimate` estimates it:
    estimate.csv and dead_reckoning.csv (column after column) and
    estimate.json; `smoothed` is the smoothed map's cutoff [m], None for
    the scenario's terrain."""
def plan_info(text: str, origin: str, dir: str, base_text: Optional[str] = None) -> tuple[int, str, str]: ...
def plan_task(text: str, origin: str, dir: str, index: int, base_text: Optional[str] = None) -> str: ...
def wheel_test(
    soil: str,
    soil_text: Optional[str],
    radius: float,
    width: float,
    load: float,
    slips: list[float],
    slip_angle_deg: float,
) -> tuple[list[str], bytes]: ...
def builtins() -> list[str]: ...
