"""A run's sensor log from Python (`Result.sensors`) and its estimation
(`rover.estimate`) against the command line's `rover simulate` and
`rover estimate`, and the errors of a log or a truth that does not fit."""

import json
import math

import numpy as np
import pytest

import rover
from conftest import REPO

#: What the two outputs' summaries differ in from run to run.
TIMING = {"wall_time", "step_us"}


def scenario_text() -> str:
    """Fig. 13's observer run (scenarios/fig13_observer.toml), short: 8 s,
    0.5 s of settling and 0.1 m/s, so that the rover crosses the rough
    ground within the run (the shipped run settles for 6 s and drives at
    0.05 m/s for 40 s); with a position fix at 1 Hz and a heading fix at
    2 Hz besides the IMU and the encoders, so that the log has columns
    empty where no fix is due."""
    text = (REPO / "scenarios" / "fig13_observer.toml").read_text()
    for old, new in (("duration = 40.0", "duration = 8.0"), ("settle = 6.0", "settle = 0.5"), ("speed = 0.05", "speed = 0.1")):
        assert old in text, old
        text = text.replace(old, new)
    return text + "\n[sensors.position_fix]\nrate = 1.0\nsigma = 0.05\n\n[sensors.heading_fix]\nrate = 2.0\nsigma = 0.01\n"


@pytest.fixture(scope="module")
def scenario(tmp_path_factory):
    path = tmp_path_factory.mktemp("estimate") / "observer.toml"
    path.write_text(scenario_text())
    return path


@pytest.fixture(scope="module")
def run(scenario):
    r = rover.simulate(scenario)
    assert r.status == "completed", r.error
    return r


@pytest.fixture(scope="module")
def estimated(scenario, run):
    return rover.estimate(scenario, run.sensors, truth=run)


def read_table(path, empty_is_nan=False):
    """A CSV's columns, parsed with Python's float (exact for shortest
    forms), an empty cell as NaN where allowed."""
    lines = path.read_text().splitlines()
    names = lines[0].split(",")

    def number(cell):
        if cell == "" and empty_is_nan:
            return math.nan
        return float(cell)

    rows = np.array([[number(c) for c in line.split(",")] for line in lines[1:]])
    return {n: rows[:, i] for i, n in enumerate(names)}


def assert_same_bits(a: dict, b: dict):
    """The same columns in the same order, each the same 64-bit patterns
    (NaN where NaN), not merely close values."""
    assert list(a) == list(b)
    for name in a:
        assert a[name].shape == b[name].shape, name
        assert np.array_equal(a[name].view(np.uint64), b[name].view(np.uint64)), name


def without_timing(summary):
    return {k: v for k, v in summary.items() if k not in TIMING}


@pytest.fixture(scope="module")
def command_line(cli, scenario):
    """`rover simulate` and `rover estimate` of the scenario: the folders
    of their outputs (the estimate measured against the run.csv beside
    the log)."""
    folder = scenario.parent
    cli("simulate", "--scenario", scenario, "--out", folder / "run", "--quiet", "--no-plots")
    cli("estimate", "--scenario", scenario, "--sensors", folder / "run" / "sensors.csv", "--out", folder / "est", "--no-plots")
    return folder / "run", folder / "est"


def test_simulate_gives_the_sensor_log_of_the_command_line_bit_for_bit(run, command_line):
    log = read_table(command_line[0] / "sensors.csv", empty_is_nan=True)
    assert_same_bits(run.sensors, log)
    n = len(run.trajectory["t"])
    assert len(run.sensors["t"]) == 10 * (n - 1) + 1  # 100 Hz against 10 Hz rows, both from t = 0
    # A fix where one is due (every 100th and 50th instant: 1 Hz and 2 Hz
    # from t = 0), NaN in between.
    for fix, every in (("fix_X", 100), ("fix_Y", 100), ("fix_Z", 100), ("fix_psi", 50)):
        assert np.array_equal(np.flatnonzero(~np.isnan(run.sensors[fix])), np.arange(0, 801, every)), fix
    assert not any(np.isnan(v).any() for k, v in run.sensors.items() if not k.startswith("fix_"))


def test_a_scenario_without_sensors_gives_no_sensor_log(data):
    assert rover.simulate(data / "slip_rough.toml").sensors is None


def test_estimate_over_arrays_is_the_command_lines_bit_for_bit(scenario, run, estimated, command_line):
    folder = command_line[1]
    assert_same_bits(estimated.estimate, read_table(folder / "estimate.csv"))
    assert_same_bits(estimated.dead_reckoning, read_table(folder / "dead_reckoning.csv"))
    expected = json.loads((folder / "estimate.json").read_text())
    assert without_timing(estimated.summary) == without_timing(expected)
    # The log and the truth as the files the command line read.
    from_files = rover.estimate(scenario, command_line[0] / "sensors.csv", truth=command_line[0] / "run.csv")
    assert_same_bits(from_files.estimate, estimated.estimate)
    assert without_timing(from_files.summary) == without_timing(estimated.summary)


def test_estimate_gives_a_row_per_sample_and_follows_the_roll(run, estimated):
    e = estimated
    assert e.status == "completed" and e.error is None
    samples = len(run.sensors["t"])
    state = ["X", "Y", "Z", "phi", "theta", "psi", "y1", "y2", "y3", "y4",
             "vx", "vy", "vz", "Ox", "Oy", "Oz", "dy1", "dy2", "dy3", "dy4"]
    biases = ["bgx", "bgy", "bgz", "bax", "bay", "baz"]
    assert list(e.estimate) == (
        ["t", *state, *(f"sigma_{s}" for s in state)]
        + [f"Fn{j}" for j in range(1, 5)]
        + [f"slip{j}" for j in range(1, 5)]
        + biases
        + [f"sigma_{b}" for b in biases]
    )
    assert list(e.dead_reckoning) == ["t", *state]
    for table in (e.estimate, e.dead_reckoning):
        for name, values in table.items():
            assert values.shape == (samples,), name
            assert np.isfinite(values).all(), name
        assert np.array_equal(table["t"], run.sensors["t"])
    assert (e.estimate["sigma_phi"] > 0).all()

    s = e.summary
    assert set(s) >= {"status", "error", "t_end", "samples", "map", "plant", "distance", "filter",
                      "dead_reckoning", "drift_ratio", "consistency", "wall_time", "step_us"}
    assert (s["samples"], s["t_end"], s["map"]) == (samples, 8.0, "true")
    assert set(s["filter"]) >= {"roll_deg", "pitch_deg", "yaw_deg", "velocity", "final_drift"}
    assert s["consistency"]["dof"] == 20

    # The filter's roll error at the truth's rows, from the arrays, is the
    # summary's; and small against how much the roll itself moves on the
    # rough ground (its standard deviation over the run, 0.15°).
    truth = run.trajectory
    at = np.searchsorted(e.estimate["t"], truth["t"])
    assert np.array_equal(e.estimate["t"][at], truth["t"])
    error = e.estimate["phi"][at] - truth["phi"]
    rms_deg = math.degrees(math.sqrt(np.mean(error**2)))
    assert rms_deg == pytest.approx(s["filter"]["roll_deg"], rel=1e-9)
    roll_moves_deg = math.degrees(np.std(truth["phi"]))
    assert roll_moves_deg > 0.1
    assert rms_deg < 0.1 * roll_moves_deg


def test_without_a_truth_nothing_is_measured(scenario, run, estimated):
    e = rover.estimate(scenario, run)  # a Result is taken for its sensor log
    assert_same_bits(e.estimate, estimated.estimate)
    for key in ("distance", "filter", "dead_reckoning", "drift_ratio", "consistency"):
        assert e.summary[key] is None, key


def test_the_smoothed_map_is_the_one_the_summary_names(scenario, run, estimated):
    e = rover.estimate(scenario, run.sensors, truth=run, map="smoothed", smooth_cutoff=1.0)
    assert e.summary["map"] == "smoothed below 1 m"
    assert not np.array_equal(e.estimate["Z"], estimated.estimate["Z"])
    with pytest.raises(ValueError, match=r'^map: expected "true" .* or "smoothed" .*, got \'orbital\''):
        rover.estimate(scenario, run.sensors, map="orbital")
    with pytest.raises(ValueError, match=r"^smooth_cutoff: .* must be > 0 m, got -1.0"):
        rover.estimate(scenario, run.sensors, map="smoothed", smooth_cutoff=-1.0)


def changed(sensors, name, f):
    """A copy of the log with column `name` replaced by f(values) (None:
    removed)."""
    out = {k: v.copy() for k, v in sensors.items()}
    value = f(out.get(name))
    if value is None:
        del out[name]
    else:
        out[name] = value
    return out


def with_value(i, v):
    def f(values):
        values[i] = v
        return values

    return f


LISTING = (
    "t,gx,gy,gz,ax,ay,az,enc1,enc2,enc3,enc4,susp1,susp2,susp3,susp4,fix_X,fix_Y,fix_Z,fix_psi,"
    "tau1,tau2,tau3,tau4,delta1,delta2,delta3,delta4"
)

BAD_LOGS = [
    (
        "gz",
        lambda v: None,
        "error: sensors: no column `gz`, which [sensors.imu] declares (an IMU reads it)\n"
        f"  = help: the columns of this declaration are {LISTING}",
    ),
    (
        "enc5",
        lambda v: np.zeros(801),
        "error: sensors[\"enc5\"]: the rover has 4 wheels: there is no wheel 5\n"
        f"  = help: the columns of this declaration are {LISTING}",
    ),
    (
        "gyro_x",
        lambda v: np.zeros(801),
        "error: sensors[\"gyro_x\"]: `gyro_x` is no sensor column\n"
        f"  = help: the columns of this declaration are {LISTING}",
    ),
    (
        "ax",
        lambda v: v[:-1],
        "error: sensors[\"ax\"]: 800 values, where `t` has 801\n"
        "  = help: one value per sensor instant in every column (NaN in a fix's columns where no fix is due)",
    ),
    (
        "gy",
        with_value(10, math.inf),
        "error: sensors[\"gy\"][10]: the reading is inf\n"
        "  = help: a reading is a finite number: NaN stands for no fix, in a fix's columns only",
    ),
    (
        "tau3",
        with_value(400, math.nan),
        "error: sensors[\"tau3\"][400]: the reading is NaN\n"
        "  = help: a reading is a finite number: NaN stands for no fix, in a fix's columns only",
    ),
    (
        "fix_Z",
        with_value(100, math.nan),
        "error: sensors[\"fix_X\"][100]: a position fix has some of fix_X, fix_Y, fix_Z and not the others\n"
        "  = help: a position fix gives all three coordinates, or none (NaN in all three)",
    ),
    (
        "t",
        lambda v: v * 1.5,
        "error: sensors[\"t\"][1]: t = 0.015 is not sensor instant 1 at rate = 100 Hz: t = 0.01\n"
        "  = help: element k of `t` is at t = k / rate from t = 0, every 0.01 s with none missing;"
        " check that [sensors] rate is the one the log was written with",
    ),
    (
        "gx",
        lambda v: np.stack([v, v], axis=1),
        "error: sensors[\"gx\"]: an array of shape (801, 2), not one value per instant\n"
        "  = help: the sensors.csv columns of the scenario's [sensors], each a 1-D array of one value per"
        " sensor instant (NaN in a fix's columns where no fix is due), as rover.simulate(...).sensors gives them",
    ),
]


@pytest.mark.parametrize("name,change,message", BAD_LOGS, ids=[f"{b[0]}-{i}" for i, b in enumerate(BAD_LOGS)])
def test_a_log_that_does_not_fit_is_refused_naming_the_column(scenario, run, name, change, message):
    with pytest.raises(rover.RoverError) as e:
        rover.estimate(scenario, changed(run.sensors, name, change), truth=run)
    assert str(e.value) == message


def test_a_column_of_other_than_numbers_is_refused_naming_it(scenario, run):
    log = changed(run.sensors, "az", lambda v: ["level"] * len(v))
    with pytest.raises(rover.RoverError, match=r'^error: sensors\["az"\]: not numbers: '):
        rover.estimate(scenario, log)
    with pytest.raises(TypeError, match=r"^sensors: a path or a mapping of column name to array .*, not list"):
        rover.estimate(scenario, list(run.sensors.values()))


def test_a_truth_that_does_not_fit_is_refused_naming_the_column(scenario, run):
    truth = dict(run.trajectory)
    del truth["dy3"]
    with pytest.raises(rover.RoverError) as e:
        rover.estimate(scenario, run.sensors, truth=truth)
    assert str(e.value).startswith("error: truth: no column `dy3`: this is not a run of this rover\n  = help: ")
    truth = changed(run.trajectory, "theta", with_value(7, math.nan))
    with pytest.raises(rover.RoverError) as e:
        rover.estimate(scenario, run.sensors, truth=truth)
    assert str(e.value).startswith('error: truth["theta"][7]: the value is NaN, not a finite number\n')


def test_a_log_file_that_does_not_fit_is_refused_at_its_line(scenario, run, command_line, tmp_path):
    lines = (command_line[0] / "sensors.csv").read_text().splitlines()
    del lines[5]
    bad = tmp_path / "sensors.csv"
    bad.write_text("\n".join(lines) + "\n")
    with pytest.raises(rover.RoverError) as e:
        rover.estimate(scenario, bad)
    assert str(e.value).startswith(f"error: {bad}:6: column 1 (`t`): t = 0.05 is not the sensor instant of row 5 at rate = 100 Hz: t = 0.04\n")


def test_a_scenario_without_sensors_is_refused(data, run):
    with pytest.raises(rover.RoverError) as e:
        rover.estimate(data / "slip_rough.toml", run.sensors)
    assert str(e.value) == (
        f"error: {data / 'slip_rough.toml'}: sensors: the scenario declares no [sensors], which say what its sensor log holds\n"
        "  = help: give the scenario whose run wrote the log"
    )
    no_log = rover.simulate(data / "slip_rough.toml")
    with pytest.raises(rover.RoverError, match=r"^error: sensors: the run has no sensor log"):
        rover.estimate(data / "slip_rough.toml", no_log)


def test_a_log_and_a_truth_as_pandas_tables_estimate_as_the_arrays(scenario, run, estimated):
    pd = pytest.importorskip("pandas")
    e = rover.estimate(scenario, pd.DataFrame(run.sensors), truth=run.to_pandas())
    assert_same_bits(e.estimate, estimated.estimate)
    assert without_timing(e.summary) == without_timing(estimated.summary)
