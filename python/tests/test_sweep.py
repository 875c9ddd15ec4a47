"""Sweeps on a local Ray cluster, and the command line's indexed tasks."""

import json

import pytest

import rover
from rover.sweep import TIMING

ray = pytest.importorskip("ray")
pytest.importorskip("pyarrow")
pd = pytest.importorskip("pandas")

BASE = {
    "rover": "swing4",
    "duration": 1.0,
    "settle": 0.3,
    "output_rate": 10.0,
    "terrain": {"kind": "random", "z_r": 0.2, "seed": 1},
    "control": {"speed": {"speed": 0.1, "kp": 10.0}, "steering": {"kind": "slip", "delta_tau": 0.05}},
    "integrator": {"bdf": {"rtol": 1e-5, "atol": 1e-7}},
}
# 13 gains, one of them invalid, times 4 seeds: 52 tasks, 4 of which fail.
GRID = {"control.speed.kp": [-1.0] + [2.0 + i for i in range(12)]}
SEEDS = [1, 2, 3, 4]


@pytest.fixture(scope="module")
def local_ray():
    ray.init(num_cpus=2, include_dashboard=False, log_to_driver=False)
    yield
    ray.shutdown()


def records(out):
    return {p.name: p.read_text() for p in sorted((out / "tasks").glob("*.json"))}


def test_a_sweep_of_52_tasks_records_every_run_and_the_failed_ones(local_ray, tmp_path):
    out = tmp_path / "sweep"
    df = rover.sweep(BASE, grid=GRID, seeds=SEEDS, out=out)
    assert len(df) == 52
    assert list(df["task"]) == list(range(52))
    assert list(df.columns[:5]) == ["task", "param.control.speed.kp", "param.terrain.seed", "status", "error"]
    # Grid values in order, each with every seed.
    assert list(df["param.control.speed.kp"][:5]) == [-1.0, -1.0, -1.0, -1.0, 2.0]
    assert list(df["param.terrain.seed"][:5]) == [1, 2, 3, 4, 1]
    failed = df[df["param.control.speed.kp"] < 0]
    assert list(failed["status"]) == ["error"] * 4
    assert [e.startswith(f"error: task {t}: control.speed: gains must be finite and ≥ 0, got kp = -1") for t, e in zip(failed["task"], failed["error"])] == [True] * 4
    ok = df[df["param.control.speed.kp"] > 0]
    assert set(ok["status"]) == {"completed"}
    assert ok["t_end"].eq(1.0).all() and ok["distance_m"].gt(0).all()
    assert "final.X" in df.columns
    # The table on disk is the one returned.
    on_disk = pd.read_parquet(out / "results.parquet")
    assert on_disk.shape == df.shape
    assert list(on_disk["status"]) == list(df["status"])

    # A rerun runs nothing: the records stay as they were.
    before = records(out)
    mtimes = {p.name: p.stat().st_mtime_ns for p in (out / "tasks").glob("*.json")}
    again = rover.sweep(BASE, grid=GRID, seeds=SEEDS, out=out)
    assert records(out) == before
    assert {p.name: p.stat().st_mtime_ns for p in (out / "tasks").glob("*.json")} == mtimes
    assert again.drop(columns=list(TIMING)).equals(df.drop(columns=list(TIMING)))

    # A lost record is run again, to the same figures (deterministic).
    lost = out / "tasks" / "000017.json"
    old = json.loads(lost.read_text())
    lost.unlink()
    rover.sweep(BASE, grid=GRID, seeds=SEEDS, out=out)
    new = json.loads(lost.read_text())
    for k in TIMING:
        old.pop(k), new.pop(k)
    assert new == old


def test_another_plan_in_the_same_folder_is_refused(local_ray, tmp_path):
    out = tmp_path / "sweep"
    rover.sweep(BASE, grid={"control.speed.kp": [5.0]}, out=out)
    with pytest.raises(rover.RoverError, match="another sweep's plan"):
        rover.sweep(BASE, grid={"control.speed.kp": [6.0]}, out=out)


def test_samples_are_drawn_within_their_ranges_deterministically(local_ray, tmp_path):
    a = rover.sweep(BASE, samples=4, ranges={"control.speed.speed": [0.05, 0.15]}, sample_seed=9, out=tmp_path / "a")
    b = rover.sweep(BASE, samples=4, ranges={"control.speed.speed": [0.05, 0.15]}, sample_seed=9, out=tmp_path / "b")
    v = a["param.control.speed.speed"]
    assert v.between(0.05, 0.15).all() and v.nunique() == 4
    assert a.drop(columns=list(TIMING)).equals(b.drop(columns=list(TIMING)))


def test_the_command_lines_workers_write_the_same_records(local_ray, tmp_path, cli):
    ray_out = tmp_path / "ray"
    df = rover.sweep(BASE, grid={"control.speed.kp": [-1.0, 5.0, 8.0]}, seeds=[1, 2], out=ray_out)
    # The plan the Python sweep left, run by two command-line workers.
    plan = (ray_out / "plan.toml").read_text()
    cli_dir = tmp_path / "cli"
    cli_dir.mkdir()
    (cli_dir / "base.toml").write_text((ray_out / "base.toml").read_text())
    (cli_dir / "plan.toml").write_text(plan)
    for i in range(2):
        cli("sweep", cli_dir / "plan.toml", "--index", i, "--count", 2)
    cli("sweep", cli_dir / "plan.toml", "--gather")
    for k in range(6):
        name = f"{k:06}.json"
        a = json.loads((ray_out / "tasks" / name).read_text())
        b = json.loads((cli_dir / "tasks" / name).read_text())
        for t in TIMING:
            a.pop(t, None), b.pop(t, None)
        assert a == b
    table = pd.read_csv(cli_dir / "results.csv")
    assert list(table["status"]) == list(df["status"])
    assert list(table.columns) == list(df.columns)


def test_a_plan_whose_tasks_cannot_run_is_refused_before_any_is_submitted(local_ray, tmp_path):
    out = tmp_path / "sweep"
    with pytest.raises(rover.RoverError) as e:
        rover.sweep(BASE, grid={"control.speed.kpp": [1.0, 2.0]}, out=out)
    m = str(e.value)
    assert m.startswith(f"error: {out / 'plan.toml'}: grid.\"control.speed.kpp\" = 1.0: task 0's scenario is refused: unknown field `kpp`")
    assert "`kp`" in m
    flat = {k: v for k, v in BASE.items() if k != "terrain"}
    with pytest.raises(rover.RoverError, match="seeds: each task sets terrain.seed, which only a random terrain has"):
        rover.sweep(flat, seeds=[1, 2], out=tmp_path / "flat")
    with pytest.raises(rover.RoverError, match=r"ranges.\"control.speed.speed\": \[-1e308, 1e308\] is wider"):
        rover.sweep(BASE, samples=2, ranges={"control.speed.speed": [-1e308, 1e308]}, out=tmp_path / "wide")
    with pytest.raises(rover.RoverError, match=r"1000000000000 \(samples\).* at most 1000000"):
        rover.sweep(BASE, samples=10**12, ranges={"control.speed.speed": [0.1, 0.2]}, out=tmp_path / "many")
    # Nothing written: the same folder takes the plan once corrected.
    for folder in ("sweep", "flat", "wide", "many"):
        assert not (tmp_path / folder).exists()
    df = rover.sweep(BASE, grid={"control.speed.kp": [1.0, 2.0]}, out=out)
    assert list(df["status"]) == ["completed", "completed"]


def test_gathering_names_the_missing_and_unreadable_records_and_keeps_the_table(tmp_path):
    from rover.sweep import gather

    tasks = tmp_path / "tasks"
    tasks.mkdir()
    (tasks / "000000.json").write_text('{"task": 0, "status": "completed", "t_end": 1.0}\n')
    (tasks / "000001.json").write_text('{"task": 1, "sta')
    (tasks / "000002.json").mkdir()
    with pytest.raises(rover.RoverError) as e:
        gather(tmp_path, 4, table="csv")
    m = str(e.value)
    assert m.startswith(
        f"error: {tmp_path / 'results.csv'}: written, but 3 of 4 tasks have no result: 1 missing (task 3), "
        f"2 unreadable ({tasks / '000001.json'}: not JSON: "
    )
    assert f"; {tasks / '000002.json'}: cannot read it: Is a directory)" in m
    df = e.value.table
    assert list(df["status"]) == ["completed", "unreadable", "unreadable", "missing"]
    on_disk = pd.read_csv(tmp_path / "results.csv")
    assert list(on_disk["status"]) == list(df["status"])
    (tasks / "000002.json").rmdir()
    for i in (1, 2, 3):
        (tasks / f"{i:06}.json").write_text(json.dumps({"task": i, "status": "completed"}))
    assert list(gather(tmp_path, 4, table="csv")["status"]) == ["completed"] * 4


def test_a_rover_given_as_a_dict_or_a_loaded_rover_runs_every_task(local_ray, tmp_path):
    import tomllib

    from conftest import REPO

    path = REPO / "models" / "mer.toml"
    with open(path, "rb") as f:
        description = tomllib.load(f)
    base = {k: v for k, v in BASE.items() if k != "rover"}
    grid = {"control.speed.kp": [5.0, 10.0]}
    by_dict = rover.sweep(base, grid=grid, rover=description, out=tmp_path / "dict", table="csv")
    by_path = rover.sweep(base, grid=grid, rover=rover.load(path), out=tmp_path / "path", table="csv")
    assert list(by_dict["status"]) == ["completed", "completed"]
    assert (tmp_path / "dict" / "rover.toml").exists()
    cols = [c for c in by_dict.columns if c not in TIMING]
    assert by_dict[cols].equals(by_path[cols])
    bad = dict(description, gravity=-1.0)
    with pytest.raises(rover.RoverError, match="gravity"):
        rover.sweep(base, grid=grid, rover=bad, out=tmp_path / "bad")
    assert not (tmp_path / "bad").exists()
