//! `rover sweep`: a plan's tasks shared among indexed workers, one record
//! per task (a run that cannot start is a record too), reruns that skip
//! what exists, and the gathered table.

use std::path::{Path, PathBuf};

use rover::cli::{SweepArgs, sweep};

fn scratch(name: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join("sweep")
        .join(name);
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn args(plan: &Path, index: usize, count: usize) -> SweepArgs {
    SweepArgs {
        plan: plan.to_path_buf(),
        index,
        count,
        gather: false,
        list: false,
    }
}

#[test]
fn two_workers_run_every_task_once_and_the_table_holds_the_failed_one() {
    let dir = scratch("workers");
    std::fs::write(
        dir.join("base.toml"),
        "rover = \"swing4\"\nduration = 0.5\nsettle = 0.2\n[terrain]\nkind = \"random\"\nz_r = 0.2\n\
         [control.speed]\nspeed = 0.1\n[integrator.bdf]\nrtol = 1e-5\n",
    )
    .unwrap();
    let plan = dir.join("plan.toml");
    std::fs::write(
        &plan,
        "scenario = \"base.toml\"\nout = \"out\"\nseeds = [1, 2]\n[grid]\n\"control.speed.kp\" = [-1.0, 10.0]\n",
    )
    .unwrap();
    for i in 0..2 {
        sweep(&args(&plan, i, 2)).unwrap();
    }
    let tasks = dir.join("out").join("tasks");
    let record = |i: usize| -> serde_json::Value {
        serde_json::from_str(&std::fs::read_to_string(tasks.join(format!("{i:06}.json"))).unwrap())
            .unwrap()
    };
    for i in 0..2 {
        let r = record(i);
        assert_eq!(r["status"], "error");
        assert_eq!(r["param.control.speed.kp"], -1.0);
        let e = r["error"].as_str().unwrap();
        assert!(
            e.starts_with(&format!(
                "error: task {i}: control.speed: gains must be finite"
            )),
            "{e}"
        );
    }
    for i in 2..4 {
        let r = record(i);
        assert_eq!(r["status"], "completed");
        assert_eq!(r["param.terrain.seed"], (i - 1) as i64);
        assert_eq!(r["t_end"], 0.5);
    }
    // Other seeds, other ground.
    assert_ne!(record(2)["final.Z"], record(3)["final.Z"]);

    // A rerun skips every task: a record changed by hand stays as it is.
    let marked = tasks.join("000003.json");
    std::fs::write(&marked, "{\"task\": 3, \"status\": \"kept\"}\n").unwrap();
    sweep(&args(&plan, 0, 1)).unwrap();
    assert_eq!(record(3)["status"], "kept");

    let mut gather = args(&plan, 0, 1);
    gather.gather = true;
    sweep(&gather).unwrap();
    let table = std::fs::read_to_string(dir.join("out").join("results.csv")).unwrap();
    let mut lines = table.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    assert_eq!(
        header[..5],
        [
            "task",
            "param.control.speed.kp",
            "param.terrain.seed",
            "status",
            "error"
        ]
    );
    let rows: Vec<&str> = lines.collect();
    assert_eq!(rows.len(), 4);
    assert!(
        rows[0].starts_with("0,-1.0,1,error,\"error: task 0: control.speed"),
        "{}",
        rows[0]
    );
    assert!(rows[2].starts_with("2,10.0,1,completed,,"), "{}", rows[2]);
    assert!(rows[3].starts_with("3,,,kept,"), "{}", rows[3]);
}

#[test]
fn a_worker_index_outside_the_count_is_an_error() {
    let dir = scratch("index");
    std::fs::write(dir.join("base.toml"), "duration = 1.0\n").unwrap();
    let plan = dir.join("plan.toml");
    std::fs::write(&plan, "scenario = \"base.toml\"\n").unwrap();
    let e = sweep(&args(&plan, 2, 2)).unwrap_err().to_string();
    assert_eq!(e, "--index 2 --count 2: give 0 ≤ index < count");
    let e = sweep(&args(&dir.join("none.toml"), 0, 1))
        .unwrap_err()
        .to_string();
    assert!(e.contains("none.toml"), "{e}");
}
