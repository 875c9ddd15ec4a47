"""The FMUs of `rover export`, checked by an importer nobody here wrote:
FMPy (from PyPI) validates their model descriptions and simulates them,
and their trajectories equal `rover simulate`'s CSV at the output instants,
FMI 3.0 and 2.0, with the scenario's own controllers and with torques
given from outside as a command file gives them."""

import re
import shutil

import numpy as np
import pytest
from fmpy import read_model_description, simulate_fmu
from fmpy.validation import validate_fmu

from conftest import REPO

SCENARIO = REPO / "scenarios" / "export_rough.toml"


def read_csv(path):
    with open(path) as f:
        names = f.readline().strip().split(",")
    values = np.loadtxt(path, delimiter=",", skiprows=1, ndmin=2)
    return names, values


def export(cli, out, *args):
    r = cli("export", "fmu", *args, "--out", out)
    assert r.stdout.startswith(f"wrote {out}"), r.stdout + r.stderr
    problems = validate_fmu(str(out))
    assert problems == [], problems
    return read_model_description(str(out))


@pytest.mark.parametrize("version", ["3", "2"])
def test_fmu_trajectory_equals_simulate(cli, tmp_path, version):
    cli("simulate", "--scenario", SCENARIO, "--out", tmp_path / "sim", "--no-plots", "--quiet")
    names, csv = read_csv(tmp_path / "sim" / "run.csv")
    fmu = tmp_path / f"rover{version}.fmu"
    md = export(cli, fmu, "--scenario", SCENARIO, "--fmi", version)
    assert md.fmiVersion == ("3.0" if version == "3" else "2.0")
    variables = {v.name: v for v in md.modelVariables}
    # Every CSV column but t is an output, with its unit.
    assert [n for n in names[1:] if variables[n].causality != "output"] == []
    assert variables["X"].unit == "m" and variables["Fn1"].unit == "N"
    assert variables["tau1"].unit == "N.m" and variables["Ox"].unit == "rad/s"
    result = simulate_fmu(
        str(fmu),
        fmi_type="CoSimulation",
        output_interval=float(md.defaultExperiment.stepSize),
        stop_time=float(md.defaultExperiment.stopTime),
        output=names[1:],
    )
    assert len(result) == len(csv)
    np.testing.assert_allclose(result["time"], csv[:, 0], rtol=0, atol=1e-12)
    worst = max(np.abs(result[n] - csv[:, k]).max() for k, n in enumerate(names) if k > 0)
    assert worst <= 1e-9, worst


def test_torque_input_fmu_equals_a_command_file(cli, tmp_path):
    """swing4 without loops, driven open loop: FMPy gives the FMU the
    torques of a schedule at its communication points; `rover simulate`
    reads the same schedule as a command file (times after settling)."""
    shutil.copy(REPO / "scenarios" / "export_rough.asc", tmp_path)
    base = (
        'rover = "swing4"\nduration = 4.0\nsettle = 1.0\noutput_rate = 100.0\n'
        '[terrain]\nkind = "file"\npath = "export_rough.asc"\n'
        "[integrator.rk4]\nstep = 0.001\n"
    )
    schedule = [  # t after settling [s], tau1..tau4 [N·m], held until the next row
        (0.0, 0.2, 0.2, 0.2, 0.2),
        (1.0, 0.4, 0.1, 0.4, 0.1),
        (2.0, -0.1, 0.3, -0.1, 0.3),
    ]
    (tmp_path / "open_loop.toml").write_text(base)
    (tmp_path / "commands.csv").write_text(
        "t,tau1,tau2,tau3,tau4\n" + "".join(",".join(map(str, row)) + "\n" for row in schedule)
    )
    (tmp_path / "with_file.toml").write_text(base + '[control.commands]\nfile = "commands.csv"\n')
    cli("simulate", "--scenario", tmp_path / "with_file.toml", "--out", tmp_path / "sim", "--no-plots", "--quiet")
    names, csv = read_csv(tmp_path / "sim" / "run.csv")

    fmu = tmp_path / "open_loop.fmu"
    md = export(cli, fmu, "--scenario", tmp_path / "open_loop.toml", "--inputs", "torques")
    inputs = [v.name for v in md.modelVariables if v.causality == "input"]
    assert inputs[:4] == ["tau1_cmd", "tau2_cmd", "tau3_cmd", "tau4_cmd"]
    # The schedule as FMPy's input: zero while settling, each change a
    # repeated time (FMPy applies the value after it at that instant).
    settle = 1.0
    rows = [(0.0, 0.0, 0.0, 0.0, 0.0)]
    previous = rows[0][1:]
    for t, *tau in schedule:
        rows.append((settle + t, *previous))
        rows.append((settle + t, *tau))
        previous = tuple(tau)
    rows.append((float(md.defaultExperiment.stopTime), *previous))
    signal = np.array(rows, dtype=[("time", float)] + [(n, float) for n in inputs[:4]])
    result = simulate_fmu(
        str(fmu),
        fmi_type="CoSimulation",
        output_interval=0.01,
        stop_time=float(md.defaultExperiment.stopTime),
        input=signal,
        output=names[1:],
    )
    assert len(result) == len(csv)
    # The rover's motion: coordinates, velocities, wheel centres, to 1e-9.
    state = [n for n in names[1:] if re.fullmatch(r"[XYZ]|phi|theta|psi|v[xyz]|O[xyz]|d?y\d+|W\d+[XYZ]", n)]
    assert len(state) == 6 + 4 + 6 + 4 + 12
    worst = max(np.abs(result[n] - csv[:, names.index(n)]).max() for n in state)
    assert worst <= 1e-9, worst
    # The forces and torques too, except at the instants where the torques
    # jump: there the CSV's row already holds the new torques (the run's
    # command breakpoint), FMPy samples the outputs before it sets them.
    jumps = np.isin(np.round(csv[:, 0], 9), [round(settle + t, 9) for t, *_ in schedule])
    others = [n for n in names[1:] if n not in state]
    worst = max(np.abs(result[n][~jumps] - csv[~jumps, names.index(n)]).max() for n in others)
    assert worst <= 1e-9, worst
    # And the rover went: the torques drove it forward.
    assert csv[-1, names.index("X")] > 0.1
