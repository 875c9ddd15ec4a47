"""Sweeps on Ray: one Ray task per parameter set, the records gathered into
one table.

The plan is the command line's (`rover sweep plan.toml --index I --count
N`, docs/SCALE.md): the same tasks, numbered alike, and the same record
per task, so either route can start a sweep and the other finish it.
Ray is the scheduler: this module only submits tasks and collects what
they return, on a local Ray or on a cluster given its address.
"""

from __future__ import annotations

import json
import os
import tempfile
from pathlib import Path
from typing import Any, Mapping, Optional, Sequence, Union

from . import _native
from ._toml import dumps as _toml_dumps

#: Figures that differ from run to run of the same task (the machine's
#: speed), left out when comparing records.
TIMING = ("wall_time_s", "real_time_factor")


def _run_task(plan_text: str, origin: str, folder: str, index: int, base_text: str) -> str:
    """One task's record as JSON. A run that fails or cannot start gives a
    record saying so; anything else that goes wrong in the worker too, so
    that one task never stops the sweep."""
    try:
        return _native.plan_task(plan_text, origin, folder, index, base_text)
    except BaseException as e:  # noqa: BLE001 - recorded, not raised
        return json.dumps({"task": index, "status": "error", "error": f"error: {type(e).__name__}: {e}"})


def _require_extras(call: str, table: str):
    """Ray, pandas and (for a parquet table) pyarrow, or ImportError naming
    the extra to install: raised before the sweep writes anything. Ray."""
    from . import _require

    ray = _require("ray", call)
    _require("pandas", call)
    if table == "parquet":
        _require("pyarrow", f"{call} with table='parquet'")
    return ray


def _write_whole(path: Path, text: str) -> None:
    """Write `text` to `path` whole or not at all (a rename over it)."""
    partial = path.with_name(f"{path.name}.partial-{os.getpid()}")
    partial.write_text(text)
    partial.replace(path)


#: The file, in a sweep's folder, of a rover given as text or a dict.
ROVER_FILE = "rover.toml"


def _plan_rover(rover) -> tuple[Optional[str], Optional[str]]:
    """The plan's `rover` (a built-in name or an absolute path) and, for a
    rover given as TOML text or a dict, its text (to be written as
    ROVER_FILE, which the plan then names). Loaded first: a description
    that cannot load is refused before the plan is."""
    from . import load

    if rover is None:
        return None, None
    if isinstance(rover, Mapping):
        load(rover)
        return ROVER_FILE, _toml_dumps(rover)
    if isinstance(rover, _native.Rover):
        source, is_text = rover.__reduce__()[1]
        rover = source
        if is_text:
            return ROVER_FILE, source
    if isinstance(rover, os.PathLike) or (isinstance(rover, str) and os.path.isfile(rover)):
        return str(Path(rover).resolve()), None
    if isinstance(rover, str) and "\n" in rover:
        load(rover)
        return ROVER_FILE, rover
    if isinstance(rover, str):
        return rover, None
    raise TypeError(
        f"rover: a built-in name, a path, TOML text, a dict or a loaded rover is a rover, not {type(rover).__name__}"
    )


def _plan_text(scenario_file: str, rover, seeds, samples, sample_seed, grid, ranges) -> str:
    plan: dict[str, Any] = {"scenario": scenario_file, "out": "."}
    if rover is not None:
        plan["rover"] = rover
    if seeds is not None:
        plan["seeds"] = [int(s) for s in seeds]
    if samples:
        plan["samples"] = int(samples)
        plan["sample_seed"] = int(sample_seed)
    if grid:
        plan["grid"] = {k: list(v) for k, v in grid.items()}
    if ranges:
        plan["ranges"] = {k: list(v) for k, v in ranges.items()}
    return _toml_dumps(plan)


def sweep(
    base_scenario,
    grid: Optional[Mapping[str, Sequence]] = None,
    samples: Optional[int] = None,
    ranges: Optional[Mapping[str, Sequence[float]]] = None,
    seeds: Optional[Sequence[int]] = None,
    *,
    rover=None,
    out: Union[str, os.PathLike] = "sweep-out",
    sample_seed: int = 0,
    address: Optional[str] = None,
    table: str = "parquet",
):
    """Run ``base_scenario`` (a path, TOML text or a dict) over every
    combination of ``grid`` (dotted field -> values), and/or ``samples``
    parameter sets drawn uniformly from ``ranges`` (dotted field ->
    [low, high]), each once per terrain seed in ``seeds``; one Ray task per
    run. ``rover`` (a built-in name, a path, TOML text, a dict or a loaded
    rover) overrides the scenario's; one given as text or a dict is
    written as ``out/rover.toml``.

    ``out`` receives plan.toml (the command line's plan of this sweep),
    one record per task in tasks/, and the table: results.parquet
    (``table="parquet"``, needs pyarrow) or results.csv. A rerun on the
    same folder runs only the tasks without a record. A failed run is a
    row with its status and error. ``address`` is a Ray cluster's (None: a
    running Ray, or a local one). Returns the table as a pandas DataFrame.
    """
    from . import _noted, _scenario_source

    _require_extras("rover.sweep()", table)
    out = Path(out).resolve()
    text, origin, base, note = _scenario_source(base_scenario)
    written = origin in ("<dict>", "<string>")
    scenario_file = "base.toml" if written else str(Path(origin).resolve())
    rover, rover_text = _plan_rover(rover)
    plan_text = _plan_text(scenario_file, rover, seeds, samples, sample_seed, grid, ranges)
    plan_path = out / "plan.toml"
    if plan_path.exists() and plan_path.read_text() != plan_text:
        raise _native.RoverError(
            f"error: {plan_path}: another sweep's plan is there; give this sweep another `out` folder"
        )
    # The plan is checked before anything is written for it: a plan refused
    # leaves nothing in `out` that would stand in the way of the next (a
    # rover given as text is checked from a folder of its own meanwhile).
    with _noted(note), tempfile.TemporaryDirectory() as scratch:
        folder = str(out)
        if rover_text is not None:
            Path(scratch, ROVER_FILE).write_text(rover_text)
            folder = scratch
        _native.plan_info(plan_text, str(plan_path), folder, text)
    (out / "tasks").mkdir(parents=True, exist_ok=True)
    if written:
        _write_whole(out / scenario_file, text)
    if rover_text is not None:
        _write_whole(out / ROVER_FILE, rover_text)
    _write_whole(plan_path, plan_text)
    with _noted(note):
        return sweep_plan(plan_path, address=address, table=table)


def sweep_plan(plan: Union[str, os.PathLike], *, address: Optional[str] = None, table: str = "parquet"):
    """Run a plan file on Ray (the tasks without a record), then gather
    every record into the table; returns it as a pandas DataFrame."""
    ray = _require_extras("rover.sweep_plan()", table)

    plan_path = Path(plan).resolve()
    plan_text = plan_path.read_text()
    origin, folder = str(plan_path), str(plan_path.parent)
    count, out_dir, base_text = _native.plan_info(plan_text, origin, folder)
    out_dir = Path(out_dir)
    tasks_dir = out_dir / "tasks"
    tasks_dir.mkdir(parents=True, exist_ok=True)
    todo = [i for i in range(count) if not (tasks_dir / f"{i:06}.json").exists()]
    if todo:
        if not ray.is_initialized():
            ray.init(address=address)
        remote = ray.remote(num_cpus=1, max_retries=1)(_run_task)
        # The texts go to the object store once, not with every task.
        plan_ref, base_ref = ray.put(plan_text), ray.put(base_text)
        pending = {remote.remote(plan_ref, origin, folder, i, base_ref): i for i in todo}
        while pending:
            done, _ = ray.wait(list(pending), num_returns=1)
            for ref in done:
                i = pending.pop(ref)
                try:
                    record = ray.get(ref)
                except Exception as e:  # noqa: BLE001 - a lost worker, recorded
                    record = json.dumps({"task": i, "status": "error", "error": f"error: {e}"})
                _write_whole(tasks_dir / f"{i:06}.json", record + "\n")
    return gather(out_dir, count, table=table)


def gather(out: Union[str, os.PathLike], count: int, *, table: str = "parquet"):
    """Every task's record under ``out`` as one table (task, param.*,
    status, error, figures), written as results.parquet or results.csv.

    A task without a record is a row with status ``missing``; a record that
    cannot be read or is not a task record (a JSON object), a row with
    status ``unreadable`` and the reason as its ``error``. The table is
    written either way; then, if any task lacks its result, RoverError is
    raised naming them, the table attached as its ``table`` attribute."""
    from . import _require

    pd = _require("pandas", "rover.sweep.gather()")
    if table == "parquet":
        _require("pyarrow", "rover.sweep.gather(table='parquet')")
    if table not in ("parquet", "csv"):
        raise ValueError(f"table: 'parquet' or 'csv', not {table!r}")
    out = Path(out)
    rows, missing, unreadable = [], [], []
    for i in range(count):
        path = out / "tasks" / f"{i:06}.json"
        try:
            record = json.loads(path.read_text())
            if not isinstance(record, dict):
                raise ValueError("not a task record (a JSON object)")
        except FileNotFoundError:
            missing.append(i)
            record = {"task": i, "status": "missing"}
        except (OSError, UnicodeDecodeError, ValueError) as e:
            reason = e.strerror if isinstance(e, OSError) and e.strerror else str(e)
            if isinstance(e, json.JSONDecodeError):
                reason = f"not JSON: {e}"
            elif isinstance(e, OSError):
                reason = f"cannot read it: {reason}"
            why = f"{path}: {reason}"
            unreadable.append(why)
            record = {"task": i, "status": "unreadable", "error": why}
        rows.append(record)
    df = pd.DataFrame(rows)

    def rank(c: str) -> int:
        if c == "task":
            return 0
        if c.startswith("param."):
            return 1
        if c == "status":
            return 2
        if c == "error":
            return 3
        return 4

    df = df[sorted(df.columns, key=rank)]
    written = out / f"results.{table}"
    if table == "parquet":
        df.to_parquet(written, index=False)
    else:
        df.to_csv(written, index=False)
    if missing or unreadable:
        parts = []
        if missing:
            shown = ", ".join(map(str, missing[:10])) + (f" and {len(missing) - 10} more" if len(missing) > 10 else "")
            parts.append(f"{len(missing)} missing (task{'s' if len(missing) > 1 else ''} {shown})")
        if unreadable:
            shown = "; ".join(unreadable[:10]) + (f"; and {len(unreadable) - 10} more" if len(unreadable) > 10 else "")
            parts.append(f"{len(unreadable)} unreadable ({shown})")
        e = _native.RoverError(
            f"error: {written}: written, but {len(missing) + len(unreadable)} of {count} tasks have no result: "
            + ", ".join(parts)
            + "\n  = help: run the sweep again: it runs every task without a record; delete an unreadable record"
            " to run its task again"
        )
        e.table = df
        raise e
    return df
