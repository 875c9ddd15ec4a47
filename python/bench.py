"""Figures for docs/SCALE.md (a benchmark, not a test):

1. the Python overhead of one ``Simulation.step()`` call over the Rust step
   it runs: M calls of step() against one step(M) over the same steps;
2. a 200-task sweep on a local Ray against a sequential loop of the
   command line (``rover simulate`` once per task).

    python bench.py [--tasks 200] [--cli path/to/rover]
"""

import argparse
import os
import shutil
import subprocess
import tempfile
import time
from pathlib import Path

import rover
from rover._toml import dumps

STEP = {
    "rover": "swing4",
    "duration": 900.0,  # 5 × 20 000 steps of 1 ms fit; at most 10⁶ output rows
    "output_rate": 1000.0,
    "terrain": {"kind": "flat"},
    "control": {"speed": {"speed": 0.1}},
    "integrator": {"rk4": {"step": 1e-3}},
}

TASK = {
    "rover": "swing4",
    "duration": 2.0,
    "settle": 0.5,
    "output_rate": 10.0,
    "terrain": {"kind": "random", "z_r": 0.2, "seed": 1},
    "control": {"speed": {"speed": 0.1, "kp": 10.0}, "steering": {"kind": "slip", "delta_tau": 0.05}},
    "integrator": {"bdf": {"rtol": 1e-5, "atol": 1e-7}},
}


def step_overhead(m=20000, repeats=5):
    sim = rover.Simulation(None, STEP)
    best_calls = best_one = float("inf")
    for _ in range(repeats):
        sim.reset()
        t0 = time.perf_counter()
        for _ in range(m):
            sim.step()
        best_calls = min(best_calls, time.perf_counter() - t0)
        sim.reset()
        t0 = time.perf_counter()
        sim.step(m)
        best_one = min(best_one, time.perf_counter() - t0)
    rust = best_one / m
    return rust, (best_calls - best_one) / m


def sweep_vs_cli(tasks, cli):
    import ray

    work = Path(tempfile.mkdtemp(prefix="rover-bench-"))
    try:
        t0 = time.perf_counter()
        for seed in range(1, tasks + 1):
            s = dict(TASK, terrain=dict(TASK["terrain"], seed=seed))
            path = work / "s.toml"
            path.write_text(dumps(s))
            subprocess.run(
                [cli, "simulate", "--scenario", path, "--out", work / "cli", "--quiet", "--no-plots"],
                check=True,
            )
        sequential = time.perf_counter() - t0
        ray.init(include_dashboard=False, log_to_driver=False)
        t_init = time.perf_counter()
        t0 = time.perf_counter()
        df = rover.sweep(TASK, seeds=range(1, tasks + 1), out=work / "ray")
        swept = time.perf_counter() - t0
        assert (df["status"] == "completed").all()
        ray.shutdown()
        return sequential, swept, t_init
    finally:
        shutil.rmtree(work, ignore_errors=True)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--tasks", type=int, default=200)
    ap.add_argument("--cli", default=os.environ.get("ROVER_CLI", "rover"))
    a = ap.parse_args()
    rust, over = step_overhead()
    print(f"step: Rust {rust * 1e6:.2f} µs per output interval (rk4, 1 ms), Python call overhead {over * 1e6:.2f} µs")
    seq, swept, _ = sweep_vs_cli(a.tasks, a.cli)
    print(
        f"{a.tasks} tasks: sequential CLI loop {seq:.1f} s ({seq / a.tasks * 1e3:.0f} ms/task), "
        f"Ray sweep {swept:.1f} s ({swept / a.tasks * 1e3:.0f} ms/task), speed-up {seq / swept:.2f}x on {os.cpu_count()} cores"
    )


if __name__ == "__main__":
    main()
