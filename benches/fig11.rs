//! Fig. 11 of Chen & Genta (2012): the cost of the four fidelity levels,
//! on a shortened version of the paper's case (Example 2 = swing4,
//! Z_R = 0.3 on the reproduction's terrain, seed 1, V = 0.1 m/s,
//! Δτ = 0.2 N·m, 6 s settling and 14 s driving), whole runs as
//! `rover simulate` makes them (generic plant, BDF, CSV written to a sink).
//! The quasi-static level follows the full run's path. Each level's median
//! and each reduced level's median share of the full model's come from the
//! same criterion run; a level whose run stops early is timed up to the
//! stop, and said so. `cargo bench --bench fig11 -- --warm-up-time 1 --measurement-time 3`.

use std::hint::black_box;
use std::path::Path;
use std::sync::atomic::AtomicBool;
use std::time::{Duration, Instant};

use criterion::{BenchmarkId, Criterion};
use rover_scenario::output::Summary;
use rover_scenario::prepare::Prepared;

/// Simulated time of each run \[s\] (the report's Fig. 11 runs take 40 s).
const DURATION: f64 = 20.0;

/// The levels, the full model first.
const LEVELS: [&str; 4] = ["full", "simplified", "linearized", "quasi_static"];

/// The paper's shares of the full model's time (simplified, linearized,
/// quasi-static).
const PAPER: [f64; 3] = [0.70, 0.58, 0.15];

/// The scenario text of one level, as the reproduction writes it.
fn scenario(level: &str, full_csv: &Path) -> String {
    let path = if level == "quasi_static" {
        format!("path_from = \"{}\"\n", full_csv.display())
    } else {
        String::new()
    };
    format!(
        "duration = {DURATION}\nsettle = 6.0\noutput_rate = 10.0\nfidelity = \"{level}\"\n{path}{}\
         [control.speed]\nspeed = 0.1\nkp = 10.0\n\
         [control.steering]\nkind = \"slip\"\ndelta_tau = 0.2\n\
         [integrator.bdf]\nrtol = 1e-6\natol = 1e-8\nmax_order = 2\n",
        rover::cli::calibrated::terrain(0.3, 1)
    )
}

fn run(prepared: &Prepared, csv: impl std::io::Write) -> Summary {
    prepared
        .run(true, csv, &AtomicBool::new(false), |_| {})
        .unwrap()
}

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

fn main() {
    let dir = std::env::temp_dir().join(format!("rover-fig11-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let full_csv = dir.join("full.csv");
    let prepare = |level: &str| {
        Prepared::from_text(
            Some("swing4"),
            &scenario(level, &full_csv),
            &dir.join(format!("{level}.csv")),
            &dir,
        )
        .unwrap()
    };
    // The full run's path, for the quasi-static level.
    let full = prepare("full");
    run(&full, std::fs::File::create(&full_csv).unwrap());

    let mut c = Criterion::default().configure_from_args();
    let mut group = c.benchmark_group("fig11_swing4_zr0.3");
    group.sample_size(10);
    let mut medians = Vec::new();
    let mut ends = Vec::new();
    for level in LEVELS {
        let prepared = prepare(level);
        let summary = run(&prepared, std::io::sink());
        ends.push((summary.complete, summary.t_end, summary.error.clone()));
        // Criterion's own statistics, and each sample's time per run
        // kept for the shares below.
        let mut per_run = Vec::new();
        group.bench_function(BenchmarkId::new("run_20s", level), |b| {
            b.iter_custom(|iters| {
                let start = Instant::now();
                for _ in 0..iters {
                    black_box(run(&prepared, std::io::sink()).rhs_evals);
                }
                let took: Duration = start.elapsed();
                per_run.push(took.as_secs_f64() / iters as f64);
                took
            })
        });
        medians.push(median(per_run));
    }
    group.finish();
    c.final_summary();

    println!("Fig. 11, shortened (swing4, Z_R = 0.3, V = 0.1 m/s, Δτ = 0.2 N·m, {DURATION} s):");
    for (k, level) in LEVELS.iter().enumerate() {
        let (complete, t_end, error) = &ends[k];
        let stop = if *complete {
            String::new()
        } else {
            format!(
                " (stops at t = {t_end:.1} s: {}; timed up to the stop)",
                error.as_deref().unwrap_or("no reason given")
            )
        };
        let share = if k == 0 {
            String::new()
        } else {
            format!(
                ", {:.0} % of the full model's (paper: {:.0} %)",
                100.0 * medians[k] / medians[0],
                100.0 * PAPER[k - 1]
            )
        };
        println!(
            "  {level:<13} median {:.1} ms{share}{stop}",
            1e3 * medians[k]
        );
    }
    let _ = std::fs::remove_dir_all(&dir);
}
