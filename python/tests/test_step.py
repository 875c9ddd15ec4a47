"""The step-wise Simulation."""

import sys
import threading
import time

import numpy as np
import pytest

import rover
from conftest import DATA, LONG, interrupt_after


@pytest.fixture
def sim(data):
    return rover.Simulation(None, data / "slip_rough.toml")




def test_stepping_without_changes_gives_the_whole_runs_rows_bit_for_bit(data, sim):
    whole = rover.simulate(None, data / "slip_rough.toml")
    n2 = 2 * sim.dof
    row = np.empty(len(sim.columns))
    assert sim.columns == whole.columns
    for k in range(len(whole.table)):
        if k > 0:
            sim.step()
        sim.row_into(row)
        assert np.array_equal(row.view(np.uint64), whole.table[k].view(np.uint64)), k
        assert np.array_equal(sim.state, whole.table[k, 1 : 1 + n2])


def test_step_n_equals_n_steps(data):
    a = rover.Simulation(None, data / "slip_rough.toml")
    b = rover.Simulation(None, data / "slip_rough.toml")
    a.step(30)
    for _ in range(30):
        b.step()
    assert a.time == b.time == pytest.approx(30 * a.dt)
    assert np.array_equal(a.state, b.state)


def test_reset_starts_the_run_again(sim):
    first = sim.state
    sim.step(10)
    assert not np.array_equal(sim.state, first)
    sim.reset()
    assert sim.time == 0.0
    assert np.array_equal(sim.state, first)


def test_open_loop_torques_and_set_points_change_the_motion(data):
    base = rover.Simulation(None, data / "slip_rough.toml")
    pushed = rover.Simulation(None, data / "slip_rough.toml")
    faster = rover.Simulation(None, data / "slip_rough.toml")
    pushed.set_torques(np.full(pushed.wheel_count, 0.5))
    faster.set_speed(0.2)
    for s in (base, pushed, faster):
        s.step(50)
    x = lambda s: s.row["X"]  # noqa: E731
    assert x(pushed) > x(base)
    assert x(faster) > x(base)
    assert pushed.row["V_set"] == 0.1 and faster.row["V_set"] == 0.2


def test_commands_of_the_wrong_length_or_type_are_errors(sim):
    with pytest.raises(ValueError, match=r"^torques: expected 4 values \(shape \(4,\)\), one torque \[N·m\] per wheel; got shape \(3,\)$"):
        sim.set_torques(np.zeros(3))
    with pytest.raises(ValueError, match=r"^torques: expected 4 values .* got shape \(5,\)$"):
        sim.set_torques([0.0] * 5)
    with pytest.raises(TypeError, match=r"^torques: expected a sequence of numbers or a numeric array of 4 values .*; got list"):
        sim.set_torques(["a", "b", "c", "d"])
    with pytest.raises(TypeError, match=r"^torques: .*; got NoneType"):
        sim.set_torques(None)
    with pytest.raises(rover.RoverError, match="finite"):
        sim.set_torques(np.array([0.0, np.nan, 0.0, 0.0]))
    with pytest.raises(rover.RoverError, match="not steerable|steer"):
        sim.set_steering(np.full(4, 0.1))
    with pytest.raises(ValueError, match=r"state: expected a 1-D float64 array of 20 values \(shape \(20,\)\), got shape \(3,\)$"):
        sim.state_into(np.empty(3))


def test_torques_are_taken_from_lists_tuples_and_any_numeric_array(data):
    runs = {}
    given = {
        "float64 array": np.full(4, 0.5),
        "list": [0.5, 0.5, 0.5, 0.5],
        "tuple": (0.5, 0.5, 0.5, 0.5),
        "float32 array": np.full(4, 0.5, dtype=np.float32),
        "int list": [1, 1, 1, 1],
        "strided view": np.full(8, 0.5)[::2],
    }
    for name, torques in given.items():
        s = rover.Simulation(None, data / "slip_rough.toml")
        s.set_torques(torques)
        s.step(20)
        runs[name] = s.state
    plain = rover.Simulation(None, data / "slip_rough.toml")
    plain.step(20)
    assert not np.array_equal(runs["float64 array"], plain.state)
    for name in ("list", "tuple", "float32 array", "strided view"):
        assert np.array_equal(runs[name], runs["float64 array"]), name
    assert not np.array_equal(runs["int list"], runs["float64 array"])


def test_per_wheel_arrays_of_another_shape_are_refused_naming_the_shapes(sim):
    cases = [
        (np.full((2, 2), 5.0), "(2, 2)"),
        (np.full((1, 4), 5.0), "(1, 4)"),
        (np.full((4, 1), 5.0), "(4, 1)"),
        (np.array(5.0), "()"),
    ]
    for torques, shape in cases:
        with pytest.raises(ValueError) as e:
            sim.set_torques(torques)
        assert str(e.value) == f"torques: expected 4 values (shape (4,)), one torque [N·m] per wheel; got shape {shape}"
        with pytest.raises(ValueError, match=r"^steering: .* got shape "):
            sim.set_steering(torques)
    with pytest.raises(ValueError, match=r"^row: expected a 1-D float64 array of \d+ values"):
        sim.row_into(np.empty((1, len(sim.columns))))
    # Nothing refused was applied: the run goes on as before.
    sim.step(5)
    ref = rover.Simulation(None, DATA / "slip_rough.toml")
    ref.step(5)
    assert np.array_equal(sim.state, ref.state)


def test_a_steering_set_point_needs_a_steering_loop(data):
    s = rover.Simulation(None, {"rover": "swing4", "duration": 1.0})
    with pytest.raises(rover.RoverError, match="slip or Ackermann"):
        s.set_steering_setpoint(0.1)
    with pytest.raises(rover.RoverError, match=r"\[control.speed\]"):
        s.set_speed(0.1)


def test_a_failed_run_raises_and_stays_failed_until_reset():
    # Spun about x with a roll-over limit far below the first step's roll.
    s = rover.Simulation(
        None,
        {
            "rover": "swing4",
            "duration": 5.0,
            "rollover_limit_deg": 0.0001,
            "initial": {"z": 0.5, "attitude_deg": [0.0, 0.0, 0.0], "angular_velocity": [0.5, 0.0, 0.0]},
        },
    )
    with pytest.raises(rover.RunFailed, match="rolled over") as first:
        s.step(40)
    assert s.error == str(first.value)
    with pytest.raises(rover.RunFailed):
        s.step()
    s.reset()
    assert s.error is None and s.time == 0.0
    # Deterministic: the same failure again.
    with pytest.raises(rover.RunFailed) as again:
        s.step(40)
    assert str(again.value) == str(first.value)


def test_long_steps_let_other_threads_run(data):
    sim = rover.Simulation(None, data / "slip_rough.toml")
    count = [0]
    stop = threading.Event()

    def counter():
        while not stop.is_set():
            count[0] += 1

    # A long switch interval: the counter runs during the steps only if
    # they release the GIL (held, the count could not move at all).
    old = sys.getswitchinterval()
    sys.setswitchinterval(0.05)
    worker = threading.Thread(target=counter)
    worker.start()
    try:
        time.sleep(0.01)
        before = count[0]
        sim.step(2000)
        during = count[0] - before
    finally:
        stop.set()
        worker.join()
        sys.setswitchinterval(old)
    assert during > 1000, during


def test_ctrl_c_stops_a_long_step_at_the_last_step_completed():
    sim = rover.Simulation(None, LONG)
    with interrupt_after(0.3) as sent, pytest.raises(KeyboardInterrupt):
        sim.step(10**9)
    # The step stops within a second of the signal.
    assert sent and time.monotonic() - sent[0] < 1.0
    k = round(sim.time / sim.dt)
    assert k > 0 and sim.time < LONG["duration"]
    assert sim.error is None and sim.row["t"] == sim.time
    # The state is the run's at that step, and the run steps on from it.
    ref = rover.Simulation(None, LONG)
    ref.step(k)
    assert ref.time == sim.time
    assert np.array_equal(ref.state, sim.state)
    assert sim.step(2) == ref.step(2)
    assert np.array_equal(ref.state, sim.state)
