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

#[test]
fn gathering_with_a_record_missing_or_unreadable_writes_the_table_and_fails_naming_them() {
    let dir = scratch("gather");
    std::fs::write(
        dir.join("base.toml"),
        "rover = \"swing4\"\nduration = 0.5\n[control.speed]\nspeed = 0.1\n",
    )
    .unwrap();
    let plan = dir.join("plan.toml");
    std::fs::write(
        &plan,
        "scenario = \"base.toml\"\nout = \"out\"\n[grid]\n\"control.speed.kp\" = [1.0, 2.0, 3.0, 4.0, 5.0]\n",
    )
    .unwrap();
    let tasks = dir.join("out").join("tasks");
    std::fs::create_dir_all(&tasks).unwrap();
    // Task 0 done, 1 cut short, 2 not JSON, 3 a folder, 4 never run.
    std::fs::write(
        tasks.join("000000.json"),
        "{\"task\": 0, \"status\": \"completed\", \"t_end\": 0.5}\n",
    )
    .unwrap();
    std::fs::write(tasks.join("000001.json"), "{\"task\": 1, \"sta").unwrap();
    std::fs::write(tasks.join("000002.json"), "[1, 2]\n").unwrap();
    std::fs::create_dir_all(tasks.join("000003.json")).unwrap();
    let mut gather = args(&plan, 0, 1);
    gather.gather = true;
    let e = sweep(&gather).unwrap_err().user_message();
    let table = dir.join("out").join("results.csv");
    assert!(
        e.starts_with(&format!(
            "error: {}: written, but 4 of 5 tasks have no result: 1 missing (task 4), 3 unreadable ({}: not JSON: EOF",
            table.display(),
            tasks.join("000001.json").display()
        )),
        "{e}"
    );
    assert!(
        e.contains(&format!(
            "{}: not a task record (a JSON object); {}: cannot read it: ",
            tasks.join("000002.json").display(),
            tasks.join("000003.json").display()
        )),
        "{e}"
    );
    assert!(e.contains("delete an unreadable record"), "{e}");
    // Each row with its task's parameters, whether its record was read or not.
    let text = std::fs::read_to_string(&table).unwrap();
    let mut lines = text.lines();
    assert_eq!(
        lines.next().unwrap(),
        "task,param.control.speed.kp,status,error,t_end"
    );
    let cells: Vec<Vec<&str>> = lines.map(|l| l.split(',').take(3).collect()).collect();
    assert_eq!(
        cells,
        [
            ["0", "", "completed"],
            ["1", "2.0", "unreadable"],
            ["2", "3.0", "unreadable"],
            ["3", "4.0", "unreadable"],
            ["4", "5.0", "missing"]
        ]
    );

    // Every record readable: the gather succeeds.
    std::fs::remove_dir(tasks.join("000003.json")).unwrap();
    for i in 1..5 {
        std::fs::write(
            tasks.join(format!("{i:06}.json")),
            format!("{{\"task\": {i}, \"status\": \"completed\"}}\n"),
        )
        .unwrap();
    }
    sweep(&gather).unwrap();
}

#[test]
fn a_plan_whose_tasks_cannot_run_is_refused_before_any_runs() {
    let dir = scratch("refused");
    std::fs::write(
        dir.join("base.toml"),
        "rover = \"swing4\"\nduration = 0.5\n[control.speed]\nspeed = 0.1\n",
    )
    .unwrap();
    let plan = dir.join("plan.toml");
    let refuse = |text: &str| -> String {
        std::fs::write(&plan, text).unwrap();
        let mut list = args(&plan, 0, 1);
        list.list = true;
        let listed = sweep(&list).unwrap_err().user_message();
        let ran = sweep(&args(&plan, 0, 1)).unwrap_err().user_message();
        assert_eq!(listed, ran);
        assert!(!dir.join("out").exists(), "a task ran");
        listed
    };
    let e = refuse(
        "scenario = \"base.toml\"\nout = \"out\"\n[grid]\n\"control.speed.sped\" = [0.1, 0.2]\n",
    );
    assert!(
        e.starts_with(&format!(
            "error: {}: grid.\"control.speed.sped\" = 0.1: task 0's scenario is refused: unknown field `sped`",
            plan.display()
        )),
        "{e}"
    );
    let e = refuse("scenario = \"base.toml\"\nout = \"out\"\nseeds = [1, 2]\n");
    assert!(
        e.contains("seeds: each task sets terrain.seed, which only a random terrain has"),
        "{e}"
    );
    let e = refuse(
        "scenario = \"base.toml\"\nout = \"out\"\nsamples = 3\n[ranges]\n\"control.speed.speed\" = [-1e308, 1e308]\n",
    );
    assert!(
        e.contains("ranges.\"control.speed.speed\": [-1e308, 1e308] is wider"),
        "{e}"
    );
    let e = refuse(
        "scenario = \"base.toml\"\nout = \"out\"\nsamples = 1000000000000\n[ranges]\n\"control.speed.speed\" = [0.1, 0.2]\n",
    );
    assert!(e.contains("1000000000000 (samples)"), "{e}");
    let e = refuse("scenario = \"base.toml\"\nout = \"out\"\nsamples = 1e18\n");
    assert!(
        e.ends_with("invalid type: floating point `1000000000000000000.0`, expected usize"),
        "{e}"
    );
}
