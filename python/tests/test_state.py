"""Reading and setting a step-wise run's state; snapshots, copies and
pickles of it."""

import copy
import pickle

import numpy as np
import pytest

import rover

#: A run whose controllers keep integral states (the heading loop's ki)
#: and whose integrator keeps a history (BDF): what a snapshot must hold.
HEADING = {
    "rover": "swing4",
    "duration": 10.0,
    "settle": 0.2,
    "output_rate": 20.0,
    "terrain": {"kind": "random", "z_r": 0.2, "seed": 5},
    "control": {
        "speed": {"speed": 0.1, "kp": 10.0},
        "steering": {"kind": "heading", "heading_deg": 10.0, "kp": 1.0, "ki": 0.5},
    },
    "integrator": {"bdf": {"rtol": 1e-6, "atol": 1e-8}},
}


def bits(a):
    return np.asarray(a, dtype=np.float64).view(np.uint64)


def second(sim):
    return round(1.0 / sim.dt)


def test_a_restored_snapshot_continues_bit_for_bit():
    sim = rover.Simulation(HEADING)
    sim.set_torques([0.2, 0.1, 0.0, -0.1])
    sim.step(second(sim))
    snap = sim.snapshot()
    assert snap.time == sim.time
    sim.step(second(sim))
    x1, t1, row1 = sim.get_state(), sim.time, np.array(list(sim.row.values()))
    sim.restore(snap)
    assert sim.time == snap.time
    sim.step(second(sim))
    x2, t2, row2 = sim.get_state(), sim.time, np.array(list(sim.row.values()))
    assert t1 == t2
    assert np.array_equal(bits(x1), bits(x2))
    assert np.array_equal(bits(row1), bits(row2))


def test_a_snapshot_holds_the_commands_and_set_points():
    sim = rover.Simulation(HEADING)
    sim.step(10)
    snap = sim.snapshot()
    sim.step(10)
    x1 = sim.get_state()
    sim.restore(snap)
    # Changed after the snapshot: restoring puts the old ones back.
    sim.set_torques([1.0, 1.0, 1.0, 1.0])
    sim.set_speed(0.3)
    sim.restore(snap)
    sim.step(10)
    assert np.array_equal(bits(sim.get_state()), bits(x1))


def test_a_snapshot_restores_into_another_simulation_of_the_same_setup_only(data):
    a = rover.Simulation(HEADING)
    a.step(15)
    b = rover.Simulation(HEADING)
    b.restore(a.snapshot())
    a.step(15)
    b.step(15)
    assert np.array_equal(bits(a.get_state()), bits(b.get_state()))
    other = rover.Simulation(None, data / "slip_rough.toml")
    with pytest.raises(ValueError, match="^snapshot: taken of a simulation of another rover or scenario"):
        other.restore(a.snapshot())
    with pytest.raises(TypeError, match="^snapshot: expected a Snapshot"):
        other.restore(a.get_state())


def test_restoring_a_snapshot_of_a_failed_run_fails_again_and_an_earlier_one_recovers():
    sim = rover.Simulation(HEADING)
    sim.step(5)
    good = sim.snapshot()
    x = sim.state
    x[sim.dof :] = 1e6  # absurd speeds: the run fails
    sim.state = x
    with pytest.raises(rover.RunFailed):
        sim.step(5)
    bad = sim.snapshot()
    sim.restore(good)
    assert sim.error is None
    sim.step(5)
    sim.restore(bad)
    assert sim.error is not None
    with pytest.raises(rover.RunFailed):
        sim.step()


def test_get_state_is_the_full_state_and_set_state_moves_the_run_there():
    a = rover.Simulation(HEADING)
    b = rover.Simulation(HEADING)
    a.step(20)
    b.step(10)
    full = a.get_state()
    assert full.shape == (a.state_size,)
    assert a.state_size >= 2 * a.dof
    assert np.array_equal(full[: 2 * a.dof], a.state)
    t = b.time
    b.set_state(full)
    assert b.time == t  # the state moves, the time stays
    assert np.array_equal(bits(b.get_state()), bits(full))
    row = b.row
    assert row["t"] == t and row["X"] == full[0]
    b.step(5)
    assert b.time > t
    # [x; w] alone keeps the internal states.
    c = rover.Simulation(HEADING)
    c.step(10)
    inner = c.get_state()[2 * c.dof :]
    c.state = list(a.state)
    assert np.array_equal(c.state, a.state)
    assert np.array_equal(c.get_state()[2 * c.dof :], inner)


def test_a_state_of_another_length_or_not_finite_is_refused_naming_both_lengths():
    sim = rover.Simulation(HEADING)
    n2, full = 2 * sim.dof, sim.state_size
    with pytest.raises(ValueError, match=rf"^state: expected {n2} values \(shape \({n2},\)\) or {full} values .*got shape \(3,\)$"):
        sim.set_state(np.zeros(3))
    with pytest.raises(ValueError, match=r"^state: value 2 is NaN: every value must be finite"):
        x = sim.state
        x[2] = np.nan
        sim.set_state(x)
    with pytest.raises(ValueError, match=rf"^state: expected {n2} values"):
        sim.state = sim.get_state() if full != n2 else np.zeros(n2 + 1)
    before = sim.get_state()
    sim.set_state(before.astype(np.float32).astype(np.float64))
    assert np.allclose(sim.get_state(), before, rtol=1e-6)


@pytest.mark.parametrize("how", ["copy", "deepcopy", "pickle"])
def test_a_copy_continues_as_the_original_and_independently(how):
    sim = rover.Simulation(HEADING)
    sim.step(7)
    sim.set_torques((0.1, 0.0, 0.0, 0.1))
    sim.step(8)
    sim.set_speed(0.15)
    sim.step(5)
    dup = {"copy": copy.copy, "deepcopy": copy.deepcopy, "pickle": lambda s: pickle.loads(pickle.dumps(s))}[how](sim)
    assert type(dup) is rover.Simulation
    assert dup.time == sim.time
    assert np.array_equal(bits(dup.get_state()), bits(sim.get_state()))
    dup.step(10)
    assert dup.time > sim.time  # independent
    sim.step(10)
    assert np.array_equal(bits(dup.get_state()), bits(sim.get_state()))


def test_a_pickled_run_restored_from_a_snapshot_or_reset_is_the_run_it_was():
    sim = rover.Simulation(HEADING)
    sim.step(10)
    snap = sim.snapshot()
    sim.set_torques([0.5] * 4)
    sim.step(10)
    sim.restore(snap)
    sim.step(3)
    back = pickle.loads(pickle.dumps(sim))
    assert np.array_equal(bits(back.get_state()), bits(sim.get_state()))
    sim.reset()
    back = pickle.loads(pickle.dumps(sim))
    assert back.time == 0.0 and np.array_equal(back.get_state(), sim.get_state())


def test_a_rover_pickles_as_what_it_was_loaded_from(data):
    for r in (rover.load("swing4"), rover.load((data.parents[2] / "models" / "mer.toml").read_text())):
        back = pickle.loads(pickle.dumps(r))
        assert (back.name, back.dof, back.wheel_names) == (r.name, r.dof, r.wheel_names)


def test_the_calls_a_pickle_replays_are_the_changes_not_every_step():
    sim = rover.Simulation(HEADING)
    for _ in range(30):
        sim.step()
        sim.set_torques([0.1, 0.1, 0.1, 0.1])  # the same torques again: no change
    snap = sim.snapshot()
    sim.step(5)
    # The snapshot shares the steps before it: those after are another entry.
    assert sim.calls() == [("step", [1.0]), ("set_torques", [0.1] * 4), ("step", [29.0]), ("step", [5.0])]
    sim.restore(snap)
    assert sim.calls() == [("step", [1.0]), ("set_torques", [0.1] * 4), ("step", [29.0])]
    sim.reset()
    assert sim.calls() == []
