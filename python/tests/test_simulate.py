"""Whole runs from Python against the command line's."""

import json
import time
import tomllib

import numpy as np
import pytest

import rover
from conftest import LONG, interrupt_after

TIMING = {"wall_time_s", "real_time_factor"}


def read_csv(path):
    """run.csv parsed with Python's float (exact for shortest forms)."""
    lines = path.read_text().splitlines()
    cols = lines[0].split(",")
    rows = [[float(c) for c in line.split(",")] for line in lines[1:]]
    return cols, np.array(rows)


def without_timing(summary):
    return {k: v for k, v in summary.items() if k not in TIMING}


@pytest.mark.parametrize("generic", [False, True])
def test_trajectory_and_summary_equal_the_command_lines_bit_for_bit(cli, data, tmp_path, generic):
    scenario = data / "slip_rough.toml"
    args = ["simulate", "--scenario", scenario, "--out", tmp_path, "--quiet", "--no-plots"]
    cli(*args, *(["--generic"] if generic else []))
    cols, table = read_csv(tmp_path / "run.csv")
    expected = json.loads((tmp_path / "summary.json").read_text())

    r = rover.simulate(None, scenario, generic=generic)
    assert r.status == "completed"
    assert r.columns == cols
    assert r.table.shape == table.shape
    # Bit for bit: the same 64-bit patterns, not merely close values.
    assert np.array_equal(r.table.view(np.uint64), table.view(np.uint64))
    assert without_timing(r.summary) == without_timing(expected)
    assert r.trajectory["X"][-1] == table[-1, cols.index("X")]


def test_a_scenario_as_a_dict_or_text_runs_as_its_file(data):
    path = data / "slip_rough.toml"
    from_file = rover.simulate("swing4", path)
    from_dict = rover.simulate(rover.load("swing4"), tomllib.loads(path.read_text()))
    from_text = rover.simulate(None, path.read_text())
    for r in (from_dict, from_text):
        assert np.array_equal(r.table, from_file.table)
        assert without_timing(r.summary) == without_timing(from_file.summary)


def test_to_pandas_gives_the_columns(data):
    pd = pytest.importorskip("pandas")
    r = rover.simulate(None, data / "slip_rough.toml")
    df = r.to_pandas()
    assert isinstance(df, pd.DataFrame)
    assert list(df.columns) == r.columns
    assert (df["t"].to_numpy() == r.trajectory["t"]).all()


@pytest.mark.parametrize("name", ["bad_gain.toml", "not_toml.toml"])
def test_errors_carry_the_command_lines_message(cli, data, tmp_path, name):
    scenario = data / name
    done = cli("simulate", "--scenario", scenario, "--out", tmp_path, "--quiet", "--no-plots", check=False)
    assert done.returncode == 2
    with pytest.raises(rover.RoverError) as e:
        rover.simulate(None, str(scenario))
    assert str(e.value) == done.stderr.rstrip("\n")


def test_a_bad_gain_is_located_at_its_line(data):
    with pytest.raises(rover.RoverError) as e:
        rover.simulate(None, data / "bad_gain.toml")
    assert f"{data / 'bad_gain.toml'}:4: control.speed" in str(e.value)


def test_an_unknown_rover_is_an_error_naming_it():
    with pytest.raises(rover.RoverError) as e:
        rover.load("no-such-rover")
    assert "no-such-rover" in str(e.value)


def test_a_loaded_rover_describes_itself():
    r = rover.load("swing4")
    assert r.name == "swing4"
    assert len(r.wheel_names) == 4
    assert r.dof == 6 + len(r.coordinate_names)
    assert r.report().startswith("rover `swing4`")


def test_a_rover_from_a_file_or_text_runs_the_generic_plant_to_the_same_numbers(data):
    from conftest import REPO

    path = REPO / "models" / "swing4.toml"
    by_name = rover.simulate("swing4", data / "slip_rough.toml", generic=True)
    for r in (rover.load(path), rover.load(path.read_text())):
        assert r.report() == rover.load("swing4").report()
        run = rover.simulate(r, data / "slip_rough.toml")
        assert run.summary["plant"] == "generic"
        assert np.array_equal(run.table, by_name.table)


def test_a_bad_description_text_is_an_error_with_its_diagnostics():
    with pytest.raises(rover.RoverError) as e:
        rover.load('name = "x"\n[body]\nmass = -1.0\n')
    assert "error" in str(e.value) and "<string>" in str(e.value)


def test_each_column_has_its_unit_from_the_rover_description(data):
    r = rover.simulate(None, data / "slip_rough.toml")
    sim = rover.Simulation(None, data / "slip_rough.toml")
    assert sim.columns == r.columns
    assert sim.units == [r.units[c] for c in r.columns]
    assert (r.units["t"], r.units["X"], r.units["phi"]) == ("s", "m", "rad")
    assert (r.units["vx"], r.units["Ox"]) == ("m/s", "rad/s")
    assert (r.units["Fn1"], r.units["tau1"], r.units["V_set"]) == ("N", "N·m", "m/s")
    # swing4's suspension coordinates are arm angles.
    assert (r.units["y1"], r.units["dy1"], r.units["y0_1"]) == ("rad", "rad/s", "rad")


SOIL_CLIMB = """
rover = "mer"
duration = 8.0
settle = 2.0
output_rate = 10.0

[terrain]
kind = "slope"
angle_deg = 5.0
soil = "dry_sand"

[control.speed]
speed = 0.05
kp = 500.0
ki = 1000.0
"""


def test_a_rover_on_soil_slips_and_sinks_from_python():
    r = rover.simulate(None, SOIL_CLIMB)
    assert r.status == "completed"
    for c in ("spin1", "slip1", "slip_angle1", "sinkage6", "T3"):
        assert c in r.columns
    assert (r.units["slip1"], r.units["sinkage6"], r.units["spin1"]) == ("1", "m", "rad/s")
    after = r.trajectory["t"] > 3.0
    slip = r.trajectory["slip1"][after]
    assert (slip > 0.05).all() and (slip < 0.5).all()
    assert (r.trajectory["sinkage1"][after] > 0.01).all()
    soil = r.summary["soil"]
    assert [w["wheel"] for w in soil] == [1, 2, 3, 4, 5, 6]
    # The step-wise run carries the same columns, with their units.
    sim = rover.Simulation(None, SOIL_CLIMB)
    assert sim.columns == r.columns
    assert sim.units == [r.units[c] for c in r.columns]


def test_a_rover_that_cannot_climb_the_soil_is_embedded():
    steep = SOIL_CLIMB.replace("angle_deg = 5.0", "angle_deg = 20.0")
    r = rover.simulate(None, steep.replace("duration = 8.0", "duration = 12.0"))
    assert r.status == "embedded"
    assert "embedded at t = " in r.summary["error"]


def test_ctrl_c_stops_a_whole_run_and_keeps_what_it_computed():
    with interrupt_after(0.3) as sent, pytest.raises(KeyboardInterrupt) as e:
        rover.simulate(None, LONG)
    # The run stops within a second of the signal.
    assert sent and time.monotonic() - sent[0] < 1.0
    r = e.value.result
    assert r.status == "interrupted"
    assert r.error.startswith("interrupted by the user at t = ")
    t = r.trajectory["t"]
    assert len(t) > 1 and np.all(np.diff(t) > 0)
    assert t[-1] < LONG["duration"]
    assert r.summary["t_end"] == pytest.approx(t[-1], abs=1e-3)
    # The rows are the run's: the same as a run stepped as far.
    sim = rover.Simulation(None, LONG)
    sim.step(len(t) - 1)
    assert np.array_equal(sim.state, r.table[-1, 1 : 1 + 2 * sim.dof])


def test_a_path_holding_an_equals_sign_is_read_as_the_file(data, tmp_path):
    folder = tmp_path / "kp=10"
    folder.mkdir()
    path = folder / "speed=0.1.toml"
    path.write_text((data / "slip_rough.toml").read_text())
    by_str = rover.simulate(None, str(path))
    by_path = rover.simulate(None, path)
    assert by_str.status == "completed"
    assert np.array_equal(by_str.table, by_path.table)
    assert rover.Simulation(None, str(path)).columns == by_str.columns


def test_a_str_naming_a_file_is_the_file_even_when_it_reads_as_toml(data, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "duration = 0.5").write_text((data / "slip_rough.toml").read_text())
    r = rover.simulate(None, "duration = 0.5")
    assert r.summary["t_end"] == 3.0
    # A pathlib.Path is always a file, whatever its name reads as.
    with pytest.raises(rover.RoverError) as e:
        rover.simulate(None, tmp_path / "duration = 1.0")
    assert str(e.value).startswith(f"error: {tmp_path / 'duration = 1.0'}: cannot read the scenario file: No such file")
    assert "note" not in str(e.value)


def test_a_scenario_string_that_fails_says_how_it_was_taken(tmp_path):
    with pytest.raises(rover.RoverError) as e:
        rover.simulate(None, 'duration = "long"')
    m = str(e.value)
    assert m.startswith("error: <string>")
    assert m.endswith("= note: the scenario string was taken as TOML text: it holds `=` and no file of that name exists (for a file, give its path as pathlib.Path)")
    missing = str(tmp_path / "kp=10.toml")
    with pytest.raises(rover.RoverError) as e:
        rover.simulate(None, missing)
    assert str(e.value) == (
        f"error: {missing}: cannot read the scenario file: No such file or directory\n"
        "  = note: the scenario string was taken as a path: it holds no line break and ends in .toml"
    )
    with pytest.raises(rover.RoverError) as e:
        rover.Simulation(None, str(tmp_path / "none"))
    assert str(e.value).endswith("= note: the scenario string was taken as a path: it holds no line break and no `=`, as TOML text would")


def test_a_rover_path_holding_a_line_break_or_equals_sign_is_read_as_the_file(tmp_path):
    from conftest import REPO

    path = tmp_path / "a=b\nc.toml"
    path.write_text((REPO / "models" / "swing4.toml").read_text())
    for source in (path, str(path)):
        assert rover.load(source).name == "swing4"
