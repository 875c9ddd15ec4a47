//! `rover reproduce`: rerun the paper's figures (MODEL.md §10) on one
//! calibrated terrain and write docs/REPRODUCTION.md with the plots, our
//! numbers beside the paper's. The prose is `reproduce/report.md`; the code
//! fills its placeholders, judges every claim (`reproduce/claims.rs`) and
//! fails the command when a claim the stored record says held stops
//! holding. `--quick` judges the same claims on shortened runs.

mod calibration;
mod claims;
mod handling;
mod runs;
pub mod steer;
mod template;

use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::time::Instant;

use clap::Args;
use rayon::prelude::*;
use rover_scenario::output::Summary;

use rover_scenario::output::write_whole;
use rover_scenario::prepare::load_rover;

use crate::error::CliError;
use calibration::{
    CHOSEN, CLOSE_DEG, CLOSE_M, EXAMPLE1_DURATION, FIG6_ROUGHNESS, FIG7_ROUGHNESS, FIG7_SPEEDS,
    FIG11_CLAIM_ROUGHNESS, FIG11_DELTA_TAU, FIG11_SPEED, Outcome, Plan, Record, SEARCH_DELTA,
    SEEDS,
};
use claims::Judged;
use runs::{Case, Field, ackermann, columns, deviations, other, rough_ratio, run_case, slip};
use template::Values;

/// The reproduction's terrain and runs, for tests that hold its claims.
pub mod calibrated {
    pub use super::runs::ACTIVE as ACTIVE_SUSPENSION;

    /// The `[terrain]` table of the report's calibrated field at roughness
    /// `z_r`, seed `seed` (flat at 0).
    pub fn terrain(z_r: f64, seed: u64) -> String {
        super::calibration::CHOSEN.terrain(z_r, seed)
    }

    /// Turning radii are fitted to G's path where G is at least this far
    /// from its start \[m\]: past the flat patch and its blend.
    pub const FIT_FROM_M: f64 = super::runs::PATCH_RADIUS + super::runs::PATCH_BLEND;
}

/// The report's prose, with `{{placeholders}}`.
const TEMPLATE: &str = include_str!("reproduce/report.md");

/// Arguments of `rover reproduce`.
#[derive(Debug, Args)]
pub struct ReproduceArgs {
    /// Where REPRODUCTION.md and its plots go.
    #[arg(long, default_value = "docs")]
    pub docs: PathBuf,
    /// Where the runs' CSVs go (not committed) [default: out/reproduction,
    /// or with `--quick` a folder in the system's temporary folder].
    #[arg(long)]
    pub work: Option<PathBuf>,
    /// Rerun the terrain search over the whole grid and store it in
    /// `<docs>/reproduction/calibration.csv` (otherwise the stored search is
    /// read and only the chosen setting is rerun); also stores which claims
    /// hold as the record (`<docs>/reproduction/claims.csv`).
    #[arg(long)]
    pub search: bool,
    /// Every claim's case in short form, one seed, on the chosen terrain:
    /// print the claims table, write no report or plots, and fail when a
    /// claim that holds in the quick form's record
    /// (`<docs>/reproduction/quick.csv`) no longer does.
    #[arg(long, conflicts_with = "search")]
    pub quick: bool,
    /// Store which claims hold now as the record the next runs are checked
    /// against (`claims.csv`, or `quick.csv` with `--quick`).
    #[arg(long)]
    pub record: bool,
}

impl ReproduceArgs {
    /// The runs' folder.
    fn work(&self) -> PathBuf {
        match (&self.work, self.quick) {
            (Some(w), _) => w.clone(),
            (None, false) => PathBuf::from("out/reproduction"),
            (None, true) => std::env::temp_dir().join("rover-reproduce-quick"),
        }
    }
}

/// Roughness of the paper's Fig. 11 cases.
const FIG11_ROUGHNESS: [f64; 3] = [0.1, 0.3, 1.0];
/// Roughness of the paper's Fig. 12 (the first Fig. 11 case).
const FIG12_ROUGHNESS: f64 = 0.1;
/// Wall time of `rover reproduce --search` on this project's 2-core
/// machine (release build), as the report states it.
const SEARCH_WALL_TIME: &str = "about 6 min (measured 2026-12-04)";
/// Steering angles of the quick form's Fig. 5 \[deg\].
const QUICK_FIG5_DELTAS: [f64; 3] = [2.0, 10.0, 30.0];
/// "Practically coincide" (Fig. 5): |R/R_k − 1| at most this.
const COINCIDE: f64 = 0.02;
/// The paper's Fig. 11 shares at Z_R = 0.3: simplified, linearized,
/// quasi-static.
const FIG11_PAPER_SHARES: [f64; 3] = [0.70, 0.58, 0.15];
/// How far from the paper's share ours may be (percentage points / 100).
const FIG11_SHARE_TOLERANCE: f64 = 0.15;
/// Speeds of the Fig. 11 speed table \[m/s\], at Z_R = 0.3.
const FIG11_SPEEDS: [f64; 4] = [0.05, 0.1, 0.2, 0.5];
/// Runs of a case whose median wall time is taken.
const TIMED_RUNS: usize = 5;
/// Steering angles of Fig. 5 \[deg\].
const FIG5_DELTAS: [f64; 6] = [2.0, 5.0, 10.0, 15.0, 20.0, 30.0];
/// Steering angles of Fig. 6 \[deg\] (the searched one among them).
const FIG6_DELTAS: [f64; 3] = [10.0, SEARCH_DELTA, 30.0];
/// Seed of the single-seed figures (8–14).
const SEED: u64 = 1;

/// Rerun every figure and write the report; an error after writing it when
/// a claim the stored record says held no longer holds. With `--quick`,
/// the short form (`--quick`).
pub fn reproduce(args: &ReproduceArgs) -> Result<PathBuf, CliError> {
    if args.quick {
        return quick(args);
    }
    let started = Instant::now();
    let figs = args.docs.join("reproduction");
    rover_files::OutputDir::create(&figs)
        .map_err(|e| CliError::io(&figs, "create the folder", e))?;
    let work = &args.work();
    let mut v = Values::default();
    let mut judged = Vec::new();

    let chosen_runs = calibration::evaluate(CHOSEN, work, &calibration::FULL)?;
    let chosen = Outcome::new(CHOSEN, chosen_runs.iter().map(|(r, _)| r.clone()).collect());
    let search = search(args, &chosen)?;
    calibration_section(&mut v, &search.outcomes)?;
    judged.extend(chosen.claims().iter().map(calibration::Claim::judged));

    fig5(&mut v, work, &figs, &mut judged)?;
    fig6(&mut v, work, &figs, &chosen_runs)?;
    fig7(&mut v, &figs, &chosen)?;
    steer::steer_section(&mut v, work, &figs)?;
    fig8(&mut v, work, &figs)?;
    fig11_12(&mut v, work, &figs, &mut judged)?;
    fig13(&mut v, work, &figs)?;
    fig15(&mut v, &figs, &chosen_runs, &chosen)?;

    let judged = claims::sorted(judged);
    let record_path = figs.join("claims.csv");
    let record = if args.search || args.record {
        write_whole(&record_path, &claims::to_record(&judged))?;
        claims::parse_record(&claims::to_record(&judged), &record_path)?
    } else {
        claims::read_record(&record_path)?
    };
    let table = claims::table(&judged, &record);
    let (held, of) = claims::tally(&judged);
    v.set("claims_table", table.clone());
    v.set("claims_held", format!("{held} of {of}"));
    v.num("wall_time_s", started.elapsed().as_secs_f64(), 0);
    let out = args.docs.join("REPRODUCTION.md");
    write_whole(&out, &template::render(TEMPLATE, &v)?)?;
    println!("{table}\n{held} of {of} claims hold.");
    check(&judged, &record, &search.outcomes)?;
    Ok(out)
}

/// `rover reproduce --quick`: every claim's case shortened, on one seed of
/// the chosen terrain. Prints the claims table and writes it to
/// `<work>/claims.md`; fails when a claim that holds in the quick form's
/// record no longer does.
fn quick(args: &ReproduceArgs) -> Result<PathBuf, CliError> {
    let started = Instant::now();
    let work = &args.work();
    let plan = &calibration::QUICK;
    let mut judged = Vec::new();
    let runs = calibration::evaluate(CHOSEN, work, plan)?;
    let chosen = Outcome::new(CHOSEN, runs.into_iter().map(|(r, _)| r).collect());
    judged.extend(chosen.claims().iter().map(calibration::Claim::judged));
    let cases = fig5_runs(work, &QUICK_FIG5_DELTAS, plan)?;
    judged.extend(fig5_claims(&QUICK_FIG5_DELTAS, &cases)?);
    for z in [FIG12_ROUGHNESS, FIG11_CLAIM_ROUGHNESS] {
        let l = levels_with(work, z, FIG11_SPEED, plan, 1)?;
        if z == FIG12_ROUGHNESS {
            judged.extend(fig12_claims(&l)?);
        } else {
            judged.extend(fig11_claims(&l));
        }
    }
    let judged = claims::sorted(judged);
    let record_path = args.docs.join("reproduction/quick.csv");
    if args.record {
        write_whole(&record_path, &claims::to_record(&judged))?;
    }
    let record = claims::read_record(&record_path)?;
    let table = claims::table(&judged, &record);
    let (held, of) = claims::tally(&judged);
    let out = work.join("claims.md");
    write_whole(
        &out,
        &format!(
            "# Quick reproduction: the claims\n\n{table}\n{held} of {of} claims hold ({:.0} s).\n",
            started.elapsed().as_secs_f64()
        ),
    )?;
    println!(
        "{table}\n{held} of {of} claims hold in the quick form ({:.0} s).",
        started.elapsed().as_secs_f64()
    );
    claims::check(
        &judged,
        &record,
        &format!(
            "a claim that holds in the quick form's record ({}) regressed",
            record_path.display()
        ),
    )?;
    Ok(out)
}

/// The search's outcomes (the chosen field's from this run).
struct Search {
    outcomes: Vec<Outcome>,
}

/// Run the grid (with `--search`) or read the stored one; the chosen field's
/// outcome is this run's.
fn search(args: &ReproduceArgs, chosen: &Outcome) -> Result<Search, CliError> {
    let path = args.docs.join("reproduction/calibration.csv");
    let stored = if args.search {
        let started = Instant::now();
        let mut records = Vec::new();
        for field in calibration::grid() {
            if field == CHOSEN {
                records.extend(chosen.records.iter().cloned());
            } else {
                let runs =
                    calibration::evaluate(field, &args.work().join("search"), &calibration::FULL)?;
                records.extend(runs.into_iter().map(|(r, _)| r));
            }
        }
        eprintln!("the search ran in {:.0} s", started.elapsed().as_secs_f64());
        write_whole(&path, &calibration::to_csv(&records))?;
        records
    } else {
        calibration::from_csv(&path)?
    };
    let mut outcomes = calibration::outcomes(&stored);
    match outcomes.iter_mut().find(|o| o.field == CHOSEN) {
        Some(o) => o.records = chosen.records.clone(),
        None => {
            return Err(other(
                "the stored search does not hold the chosen field: run `rover reproduce --search`",
            ));
        }
    }
    Ok(Search { outcomes })
}

/// Fails when a claim the stored record says held no longer holds, or when
/// the search ranks another field first.
fn check(judged: &[Judged], record: &[(String, bool)], grid: &[Outcome]) -> Result<(), CliError> {
    let mut problems = Vec::new();
    if let Err(e) = claims::check(judged, record, "a claim regressed") {
        problems.push(e.to_string());
    }
    if let Some(best) = calibration::best(grid)
        && best.field != CHOSEN
    {
        problems.push(format!(
            "the search ranks node amplitude {} m, spacing {} m above the chosen field",
            best.field.amplitude, best.field.spacing
        ));
    }
    if problems.is_empty() {
        Ok(())
    } else {
        Err(other(format!(
            "the report is written, but: {}",
            problems.join("; ")
        )))
    }
}

fn field_name(f: Field) -> String {
    format!("a = {} m, L = {} m", f.amplitude, f.spacing)
}

/// The search table and the chosen field.
fn calibration_section(v: &mut Values, grid: &[Outcome]) -> Result<(), CliError> {
    let mut t = String::from(
        "| node amplitude a [m] | node spacing L [m] | claims held | shortfall | Fig. 6 Z_R 0.1 / 0.2 | Fig. 6 Z_R 0.5 / 1 | Fig. 7 V 0.05 / 1 | passive pitch [°] | passive slides | active roll / pitch [°] | Fig. 11 quasi-static completes | Fig. 12 largest ΔX/ΔY [m]: simplified / linearized | Fig. 12 largest Δφ/Δθ/Δψ [°]: simplified / linearized |\n|---|---|---|---|---|---|---|---|---|---|---|---|---|\n",
    );
    let mut ranked: Vec<&Outcome> = grid.iter().collect();
    ranked.sort_by(|a, b| {
        let (sa, sb) = (a.score(), b.score());
        sb.0.cmp(&sa.0).then(sa.1.total_cmp(&sb.1))
    });
    for o in &ranked {
        let (held, miss) = o.score();
        let mark = if o.field == CHOSEN {
            " **(chosen)**"
        } else {
            ""
        };
        let r = |c: &str| o.ratio(c).show(2);
        let qs: Vec<&Record> = o.of_case("fig11_quasi_static").collect();
        let pos = |c: &str| o.deviation_of(c, Record::position_deviation).show(2);
        let att = |c: &str| o.deviation_of(c, Record::attitude_deviation).show(1);
        let _ = writeln!(
            t,
            "| {}{mark} | {} | {held} of {} | {miss:.2} | {} / {} | {} / {} | {} / {} | {} | {} of {} | {} / {} | {} of {} | {} / {} | {} / {} |",
            o.field.amplitude,
            o.field.spacing,
            calibration::CLAIMS.len(),
            r("fig6_zr0.1"),
            r("fig6_zr0.2"),
            r("fig6_zr0.5"),
            r("fig6_zr1"),
            r("fig7_v0.05"),
            r("fig7_v1"),
            o.quantity("fig15_passive", |r| r.max_pitch_deg).show(1),
            o.slides("fig15_passive").len(),
            o.seeds("fig15_passive"),
            o.quantity("fig15_active", |r| r.max_roll_deg).show(2),
            o.quantity("fig15_active", |r| r.max_pitch_deg).show(2),
            qs.iter().filter(|r| r.completed).count(),
            qs.len(),
            pos("fig11_simplified"),
            pos("fig11_linearized"),
            att("fig11_simplified"),
            att("fig11_linearized"),
        );
    }
    v.set("search_table", t);
    v.set("chosen", field_name(CHOSEN));
    v.num("chosen_correlation", 0.784 * CHOSEN.spacing, 2);
    v.num(
        "rms_height",
        CHOSEN.amplitude / 3f64.sqrt() * (57.0f64 / 70.0),
        3,
    );
    let slope = |z: f64| {
        z * CHOSEN.amplitude / CHOSEN.spacing * (2.0 * 7.0 / 3.0 * 57.0 / 70.0 / 3.0f64).sqrt()
    };
    v.num("rms_slope", slope(1.0), 2);
    v.num("rms_slope_02_deg", slope(0.2).atan().to_degrees(), 1);
    v.set("seeds", format!("{}", SEEDS.len()));
    v.set(
        "seed_list",
        SEEDS
            .iter()
            .map(|s| s.to_string())
            .collect::<Vec<_>>()
            .join(", "),
    );
    v.set("grid_size", format!("{}", grid.len()));
    v.set(
        "grid_amplitudes",
        calibration::AMPLITUDES.map(|a| a.to_string()).join(", "),
    );
    v.set(
        "grid_spacings",
        calibration::SPACINGS.map(|a| a.to_string()).join(", "),
    );
    v.num("patch_radius", runs::PATCH_RADIUS, 2);
    v.num("patch_blend", runs::PATCH_BLEND, 2);
    v.num("fit_from", runs::PATCH_RADIUS + runs::PATCH_BLEND, 2);
    v.set("claims_missed", missed(grid));
    v.set("search_claims", calibration::CLAIMS.len().to_string());
    v.set("search_minutes", SEARCH_WALL_TIME);
    v.num("coincide_pct", 100.0 * COINCIDE, 0);
    v.set("close_m", CLOSE_M.to_string());
    v.set("close_deg", CLOSE_DEG.to_string());
    Ok(())
}

/// For each claim the chosen field misses: the best any searched field
/// does, or that none meets it.
fn missed(grid: &[Outcome]) -> String {
    let chosen = grid.iter().find(|o| o.field == CHOSEN);
    let Some(chosen) = chosen else {
        return String::new();
    };
    let mut out = String::new();
    for (k, c) in chosen.claims().iter().enumerate() {
        if c.holds {
            continue;
        }
        let meeting: Vec<&Outcome> = grid.iter().filter(|o| o.claims()[k].holds).collect();
        let closest = grid
            .iter()
            .min_by(|a, b| a.claims()[k].shortfall.total_cmp(&b.claims()[k].shortfall));
        let _ = write!(
            out,
            "- **{} — {}.** Chosen field: {}. ",
            c.figure, c.paper, c.ours
        );
        if meeting.is_empty() {
            let _ = write!(out, "No searched field meets it");
            if let Some(b) = closest {
                let _ = write!(
                    out,
                    "; the closest, {}: {}",
                    field_name(b.field),
                    b.claims()[k].ours
                );
            }
            out.push_str(".\n");
        } else {
            // The best-ranked two (the grid is in rank order).
            let each: Vec<String> = meeting
                .iter()
                .take(2)
                .map(|o| {
                    let misses: Vec<&str> = o
                        .claims()
                        .iter()
                        .filter(|c| !c.holds)
                        .map(|c| c.paper)
                        .collect();
                    format!(
                        "{} (which misses: {})",
                        field_name(o.field),
                        misses.join("; ")
                    )
                })
                .collect();
            let more = match meeting.len().saturating_sub(2) {
                0 => String::new(),
                1 => " (and by one more field, ranked lower)".to_owned(),
                n => format!(" (and by {n} more fields, ranked lower)"),
            };
            let _ = writeln!(out, "Met by {}{more}.", each.join(", and by "));
        }
    }
    if out.is_empty() {
        out.push_str("The chosen field meets every claim.\n");
    }
    out
}

fn chart(
    stem: &Path,
    title: &str,
    x: &str,
    y: &str,
    series: Vec<rover_plot::Series>,
) -> Result<(), CliError> {
    let files = rover_plot::line_chart(stem, title, x, y, &series).map_err(other)?;
    for f in files {
        if f.extension().is_some_and(|x| x == "svg") {
            let _ = std::fs::remove_file(f);
        }
    }
    Ok(())
}

fn series(name: &str, points: Vec<(f64, f64)>, markers: bool) -> rover_plot::Series {
    rover_plot::Series {
        name: name.into(),
        points,
        markers,
    }
}

fn plot_case(case: &Case, rover: &str, dir: &Path) -> Result<(), CliError> {
    let spec = load_rover(rover, None)?;
    let meta = rover_plot::PlotMeta {
        title: format!(
            "{} ({})",
            spec.name,
            dir.file_name().and_then(|s| s.to_str()).unwrap_or("")
        ),
        coordinate_names: spec.coordinate_names.clone(),
        angular: spec.coordinate_linear.iter().map(|l| !l).collect(),
        wheel_names: spec.wheel_names.clone(),
        settle_time: runs::SETTLE,
        ..Default::default()
    };
    rover_plot::plot_run(&case.csv, dir, &meta).map_err(other)?;
    // Keep the PNGs in docs/ (the SVGs are regenerated on demand).
    for e in std::fs::read_dir(dir).map_err(other)?.flatten() {
        if e.path().extension().is_some_and(|x| x == "svg") {
            let _ = std::fs::remove_file(e.path());
        }
    }
    Ok(())
}

fn fmt_opt(x: Option<f64>, digits: usize) -> String {
    x.map_or("—".into(), |x| format!("{x:.digits$}"))
}

/// The Fig. 5 runs: flat ground, V = 0.05 m/s, one per steering angle.
fn fig5_runs(work: &Path, deltas: &[f64], plan: &Plan) -> Result<Vec<Case>, CliError> {
    let flat = Field {
        amplitude: 0.0,
        spacing: 1.0,
    }
    .terrain(0.0, 0);
    deltas
        .par_iter()
        .map(|d| {
            run_case(
                "exomars",
                &ackermann(&flat, 0.05, *d, plan.example1),
                &work.join(format!("fig5/delta{d}.csv")),
            )
        })
        .collect()
}

/// The single-track model's (R_k, R) from δ₁ = 2° to 30° in steps of 0.5°.
fn single_track_curve(bicycle: &handling::SingleTrack) -> Vec<(f64, f64)> {
    (4..=60)
        .filter_map(|k| {
            let d = (0.5 * k as f64).to_radians();
            Some((bicycle.ackermann(d).1, bicycle.radius(d, 0.05)?))
        })
        .collect()
}

/// Fig. 5's claims: the simulated and the single-track radii practically
/// coincide with the kinematic one.
fn fig5_claims(deltas: &[f64], cases: &[Case]) -> Result<Vec<Judged>, CliError> {
    let spec = load_rover("exomars", None)?;
    let bicycle = handling::SingleTrack::new(&spec.model);
    let mut worst = (0.0f64, 0.0);
    let mut missing = Vec::new();
    for (d, c) in deltas.iter().zip(cases) {
        match (c.summary.kinematic_radius, c.summary.turning_circle) {
            (Some(rk), Some(circle)) if c.summary.complete => {
                let dev = (circle.radius / rk - 1.0).abs();
                if dev >= worst.0 {
                    worst = (dev, *d);
                }
            }
            _ => missing.push(format!("{d}°")),
        }
    }
    let (curve_worst, at) = single_track_curve(&bicycle)
        .iter()
        .map(|(rk, r)| ((r / rk - 1.0).abs(), *rk))
        .fold((0.0f64, 0.0), |a, b| if b.0 > a.0 { b } else { a });
    let mut full_ours = format!(
        "largest |R/R_k − 1| {:.2} % (δ₁ = {}°; δ₁ = {})",
        100.0 * worst.0,
        worst.1,
        deltas
            .iter()
            .map(|d| format!("{d}"))
            .collect::<Vec<_>>()
            .join(", ")
    );
    if !missing.is_empty() {
        let _ = write!(full_ours, "; no radius at {}", missing.join(", "));
    }
    let judged = |id: &str, paper: &str, ours: String, holds: bool| Judged {
        id: id.into(),
        figure: "Fig. 5".into(),
        paper: paper.into(),
        threshold: format!(
            "flat ground, V = 0.05 m/s: |R/R_k − 1| ≤ {:.0} % at every δ₁ from 2° to 30°",
            100.0 * COINCIDE
        ),
        ours,
        holds,
        gate: true,
    };
    Ok(vec![
        judged(
            "fig5_full_kinematic",
            "the simulated radius and the kinematic one practically coincide",
            full_ours,
            missing.is_empty() && worst.0 <= COINCIDE,
        ),
        judged(
            "fig5_single_track",
            "the uncoupled handling model's radius practically coincides with them",
            format!(
                "single-track model: largest |R/R_k − 1| {:.2} % (at R_k = {at:.2} m)",
                100.0 * curve_worst
            ),
            curve_worst <= COINCIDE,
        ),
    ])
}

/// Fig. 5: flat ground, the simulated radius against the kinematic one and
/// the single-track handling model's.
fn fig5(
    v: &mut Values,
    work: &Path,
    figs: &Path,
    judged: &mut Vec<Judged>,
) -> Result<(), CliError> {
    let spec = load_rover("exomars", None)?;
    let bicycle = handling::SingleTrack::new(&spec.model);
    let cases = fig5_runs(work, &FIG5_DELTAS, &calibration::FULL)?;
    judged.extend(fig5_claims(&FIG5_DELTAS, &cases)?);
    let mut t = String::from(
        "| δ₁ [°] | R_k [m] | R [m] | R/R_k | single-track R [m] | single-track R/R_k |\n|---|---|---|---|---|---|\n",
    );
    let mut simulated = Vec::new();
    let mut worst = 0.0f64;
    for (d, c) in FIG5_DELTAS.iter().zip(&cases) {
        let s = &c.summary;
        let rk = s.kinematic_radius;
        let r = s.turning_circle.map(|c| c.radius);
        let rb = bicycle.radius(d.to_radians(), 0.05);
        if let (Some(rk), Some(r)) = (rk, r) {
            simulated.push((rk, r));
            worst = worst.max((r / rk - 1.0).abs());
        }
        let ratio = |x: Option<f64>| fmt_opt(x.zip(rk).map(|(x, k)| x / k), 3);
        let _ = writeln!(
            t,
            "| {d} | {} | {} | {} | {} | {} |",
            fmt_opt(rk, 3),
            fmt_opt(r, 3),
            ratio(r),
            fmt_opt(rb, 3),
            ratio(rb)
        );
    }
    let curve = single_track_curve(&bicycle);
    let kin: Vec<(f64, f64)> = curve.iter().map(|p| (p.0, p.0)).collect();
    let bicycle_worst = curve
        .iter()
        .map(|(rk, r)| (r / rk - 1.0).abs())
        .fold(0.0, f64::max);
    chart(
        &figs.join("fig5"),
        "Fig. 5 — R against R_k, flat ground, V = 0.05 m/s",
        "R_k [m]",
        "R [m]",
        vec![
            series("kinematic, R = R_k", kin, false),
            series("single-track handling model", curve, false),
            series("simulated (full model)", simulated, true),
        ],
    )?;
    v.set("fig5_table", t);
    v.num("fig5_worst_pct", 100.0 * worst, 2);
    v.num("fig5_bicycle_worst_pct", 100.0 * bicycle_worst, 2);
    v.set(
        "fig5_axles",
        bicycle
            .axles
            .iter()
            .map(|a| format!("x = {:.3} m, C = {:.0} N/rad", a.x, a.stiffness))
            .collect::<Vec<_>>()
            .join("; "),
    );
    v.num("fig5_mass", bicycle.mass, 1);
    Ok(())
}

/// Fig. 6: R/R_k against roughness for three steering angles, each mean
/// and spread over the seeds.
fn fig6(
    v: &mut Values,
    work: &Path,
    figs: &Path,
    chosen: &[(Record, Case)],
) -> Result<(), CliError> {
    let extra: Vec<(f64, u64, f64)> = FIG6_DELTAS
        .iter()
        .filter(|&&d| d != SEARCH_DELTA)
        .flat_map(|&d| {
            FIG6_ROUGHNESS
                .iter()
                .flat_map(move |&z| SEEDS.iter().map(move |&s| (d, s, z)))
        })
        .collect();
    let runs: Vec<(f64, u64, f64, Option<f64>)> = extra
        .par_iter()
        .map(|&(d, seed, z)| {
            let text = ackermann(&CHOSEN.terrain(z, seed), 0.05, d, EXAMPLE1_DURATION);
            let case = run_case(
                "exomars",
                &text,
                &work.join(format!("fig6/delta{d}/seed{seed}/zr{z}.csv")),
            )?;
            Ok((d, seed, z, rough_ratio(&case)?))
        })
        .collect::<Result<_, CliError>>()?;
    let mut t = String::from("| Z_R |");
    for d in FIG6_DELTAS {
        let _ = write!(t, " δ₁ = {d}° |");
    }
    t.push_str("\n|---|");
    t.push_str(&"---|".repeat(FIG6_DELTAS.len()));
    t.push('\n');
    let mut chart_series = Vec::new();
    let (mut band, mut no_band) = (Vec::new(), Vec::new());
    let mut table = vec![vec![String::new(); FIG6_DELTAS.len()]; FIG6_ROUGHNESS.len()];
    for (k, &d) in FIG6_DELTAS.iter().enumerate() {
        let mut means = Vec::new();
        let mut seeds = Vec::new();
        let mut samples = Vec::new();
        for (i, &z) in FIG6_ROUGHNESS.iter().enumerate() {
            let mut sample = calibration::Sample::default();
            if d == SEARCH_DELTA {
                for (r, _) in chosen
                    .iter()
                    .filter(|(r, _)| r.case == format!("fig6_zr{z}"))
                {
                    match r.ratio {
                        Some(x) => sample.values.push(x),
                        None => sample.stopped += 1,
                    }
                }
            } else {
                for (_, _, _, r) in runs.iter().filter(|x| x.0 == d && x.2 == z) {
                    match r {
                        Some(x) => sample.values.push(*x),
                        None => sample.stopped += 1,
                    }
                }
            }
            table[i][k] = sample.show(3);
            if let Some(m) = sample.mean() {
                means.push((z, m));
            }
            seeds.extend(sample.values.iter().map(|x| (z, *x)));
            samples.push(sample);
        }
        let in_band = |i: usize| {
            let s = &samples[i];
            matches!((s.mean(), s.sd()), (Some(m), Some(sd))
                if s.stopped == 0 && (calibration::BAND.0..=calibration::BAND.1).contains(&m) && sd <= calibration::BAND_WIDTH)
        };
        // Z_R = 0.1 and 0.2 are the first two rows.
        if in_band(0) && in_band(1) {
            band.push(format!("{d}°"));
        } else {
            no_band.push(format!("{d}°"));
        }
        chart_series.push(series(&format!("δ₁ = {d}°, mean"), means, false));
        chart_series.push(series(&format!("δ₁ = {d}°, each seed"), seeds, true));
    }
    for (i, z) in FIG6_ROUGHNESS.iter().enumerate() {
        let _ = writeln!(t, "| {z} | {} |", table[i].join(" | "));
    }
    chart(
        &figs.join("fig6"),
        "Fig. 6 — R/R_k against roughness, V = 0.05 m/s",
        "Z_R",
        "R/R_k",
        chart_series,
    )?;
    v.set("fig6_table", t);
    v.set(
        "fig6_band",
        match (band.is_empty(), no_band.is_empty()) {
            (true, _) => "holds at none of them".to_string(),
            (false, true) => "holds at each of them".to_string(),
            (false, false) => format!(
                "holds at δ₁ = {} and not at {}",
                band.join(", "),
                no_band.join(", ")
            ),
        },
    );
    v.set(
        "fig6_deltas",
        FIG6_DELTAS.map(|d| format!("{d}°")).join(", "),
    );
    Ok(())
}

/// Fig. 7: R/R_k against speed at Z_R = 0.3, δ₁ = 20°, over the seeds.
fn fig7(v: &mut Values, figs: &Path, chosen: &Outcome) -> Result<(), CliError> {
    let mut t =
        String::from("| V [m/s] | R/R_k | max roll [°] | max pitch [°] |\n|---|---|---|---|\n");
    let mut means = Vec::new();
    let mut seeds = Vec::new();
    for speed in FIG7_SPEEDS {
        let case = format!("fig7_v{speed}");
        let s = chosen.ratio(&case);
        let _ = writeln!(
            t,
            "| {speed} | {} | {} | {} |",
            s.show(3),
            chosen.quantity(&case, |r| r.max_roll_deg).show(1),
            chosen.quantity(&case, |r| r.max_pitch_deg).show(1)
        );
        if let Some(m) = s.mean() {
            means.push((speed, m));
        }
        seeds.extend(s.values.iter().map(|x| (speed, *x)));
    }
    chart(
        &figs.join("fig7"),
        &format!("Fig. 7 — R/R_k against speed, Z_R = {FIG7_ROUGHNESS}"),
        "V [m/s]",
        "R/R_k",
        vec![
            series("mean", means, false),
            series("each seed", seeds, true),
        ],
    )?;
    v.set("fig7_table", t);
    Ok(())
}

/// Figs. 8–9: Example 1, Z_R = 0.2, δ₁ = 5°, 40 s.
fn fig8(v: &mut Values, work: &Path, figs: &Path) -> Result<(), CliError> {
    let case = run_case(
        "exomars",
        &ackermann(&CHOSEN.terrain(0.2, SEED), 0.05, 5.0, 40.0),
        &work.join("fig8/run.csv"),
    )?;
    plot_case(&case, "exomars", &figs.join("fig8"))?;
    v.num("fig8_roll", case.summary.max_roll_deg, 1);
    v.num("fig8_pitch", case.summary.max_pitch_deg, 1);
    v.set("fig8_ratio", fmt_opt(rough_ratio(&case)?, 3));
    Ok(())
}

/// [`run_case`] `runs` times: the last run and the median wall time \[s\].
fn timed(rover: &str, text: &str, csv: &Path, runs: usize) -> Result<(Case, f64), CliError> {
    let mut times = Vec::with_capacity(runs);
    let mut last = None;
    for _ in 0..runs.max(1) {
        let case = run_case(rover, text, csv)?;
        times.push(case.summary.wall_time_s);
        last = Some(case);
    }
    times.sort_by(f64::total_cmp);
    let case = last.ok_or_else(|| other("no run"))?;
    Ok((case, times[times.len() / 2]))
}

/// One Fig. 11 case: the four levels, each timed.
struct Levels {
    full: (Case, f64),
    simplified: (Case, f64),
    linearized: (Case, f64),
    quasi_static: (Case, f64),
}

fn levels(work: &Path, z: f64, speed: f64) -> Result<Levels, CliError> {
    levels_with(work, z, speed, &calibration::FULL, TIMED_RUNS)
}

/// [`levels`] for the plan's Figs. 11–12 duration, each level timed over
/// `runs` runs.
fn levels_with(
    work: &Path,
    z: f64,
    speed: f64,
    plan: &Plan,
    runs: usize,
) -> Result<Levels, CliError> {
    let dir = work.join(format!("fig11/zr{z}_v{speed}"));
    let terrain = CHOSEN.terrain(z, SEED);
    let level = |name: &str, extra: &str| {
        timed(
            "swing4",
            &slip(
                &terrain,
                speed,
                FIG11_DELTA_TAU,
                plan.fig11,
                &format!("profile = true\n{extra}"),
            ),
            &dir.join(format!("{name}.csv")),
            runs,
        )
    };
    Ok(Levels {
        full: level("full", "fidelity = \"full\"")?,
        simplified: level("simplified", "fidelity = \"simplified\"")?,
        linearized: level("linearized", "fidelity = \"linearized\"")?,
        quasi_static: level(
            "quasi_static",
            "fidelity = \"quasi_static\"\npath_from = \"full.csv\"",
        )?,
    })
}

/// Fig. 11's cost table and Fig. 12's comparison at the first roughness.
fn fig11_12(
    v: &mut Values,
    work: &Path,
    figs: &Path,
    judged: &mut Vec<Judged>,
) -> Result<(), CliError> {
    let mut t = String::from(
        "| Z_R | full [s] | simplified | linearized | quasi-static | right-hand sides: full / simplified / linearized | full: contact / wheel law / plant / wheels / integrator and output |\n|---|---|---|---|---|---|---|\n",
    );
    let mut failures = Vec::new();
    let mut first = None;
    for z in FIG11_ROUGHNESS {
        let l = levels(work, z, FIG11_SPEED)?;
        if z == FIG11_CLAIM_ROUGHNESS {
            judged.extend(fig11_claims(&l));
        }
        let base = l.full.1;
        let share = |(c, time): &(Case, f64)| {
            if c.summary.complete {
                format!("{:.0} %", 100.0 * time / base)
            } else {
                format!("stopped at {:.1} s", c.summary.t_end)
            }
        };
        let split = l
            .full
            .0
            .summary
            .profile
            .as_ref()
            .map_or("—".to_owned(), |p| {
                let pct = |v: f64| 100.0 * v / p.total_s();
                format!(
                    "{:.0} / {:.0} / {:.0} / {:.0} / {:.0} %",
                    pct(p.contact_s),
                    pct(p.law_s),
                    pct(p.plant_s),
                    pct(p.wheels_s),
                    pct(p.integrator_and_output_s)
                )
            });
        let _ = writeln!(
            t,
            "| {z} | {base:.3} | {} | {} | {} | {} / {} / {} | {split} |",
            share(&l.simplified),
            share(&l.linearized),
            share(&l.quasi_static),
            l.full.0.summary.rhs_evals,
            l.simplified.0.summary.rhs_evals,
            l.linearized.0.summary.rhs_evals,
        );
        for (name, (c, _)) in [
            ("full", &l.full),
            ("simplified", &l.simplified),
            ("linearized", &l.linearized),
            ("quasi-static", &l.quasi_static),
        ] {
            if !c.summary.complete {
                failures.push(format!(
                    "the {name} run at Z_R = {z} stopped at t = {:.1} s ({})",
                    c.summary.t_end,
                    c.summary.error.as_deref().unwrap_or("no reason given")
                ));
            }
        }
        if first.is_none() {
            first = Some(l);
        }
    }
    v.set("fig11_table", t);
    let mut speeds = String::from(
        "| V [m/s] | full [s] | simplified | linearized | quasi-static |\n|---|---|---|---|---|\n",
    );
    for speed in FIG11_SPEEDS {
        let l = levels(work, FIG11_CLAIM_ROUGHNESS, speed)?;
        let base = l.full.1;
        let share = |(c, time): &(Case, f64)| {
            if c.summary.complete {
                format!("{:.0} %", 100.0 * time / base)
            } else {
                format!("stopped at {:.1} s", c.summary.t_end)
            }
        };
        let _ = writeln!(
            speeds,
            "| {speed} | {base:.3} | {} | {} | {} |",
            share(&l.simplified),
            share(&l.linearized),
            share(&l.quasi_static),
        );
    }
    v.set("fig11_speed_table", speeds);
    v.set(
        "fig11_failures",
        if failures.is_empty() {
            "Every run completed.".to_string()
        } else {
            format!(
                "Not timed, because they did not complete: {}.",
                failures.join("; ")
            )
        },
    );
    let l = first.ok_or_else(|| other("no Fig. 11 case"))?;
    judged.extend(fig12_claims(&l)?);
    fig12(v, work, figs, &l)
}

/// Fig. 11's claims on the Z_R = 0.3 case: judged on wall times, so
/// listed but never failing the command (`benches/fig11.rs` guards them).
fn fig11_claims(l: &Levels) -> Vec<Judged> {
    let base = l.full.1;
    let reduced = [
        ("simplified", &l.simplified),
        ("linearized", &l.linearized),
        ("quasi-static", &l.quasi_static),
    ];
    let shares: Vec<Option<f64>> = reduced
        .iter()
        .map(|(_, (c, time))| {
            (c.summary.complete && l.full.0.summary.complete).then(|| time / base)
        })
        .collect();
    let ours = reduced
        .iter()
        .zip(&shares)
        .map(|((name, (c, _)), s)| match s {
            Some(s) => format!("{name} {:.0} %", 100.0 * s),
            None => format!("{name} stopped at {:.1} s", c.summary.t_end),
        })
        .collect::<Vec<_>>()
        .join(", ");
    let judged = |id: &str, paper: &str, threshold: &str, holds: bool| Judged {
        id: id.into(),
        figure: "Fig. 11".into(),
        paper: paper.into(),
        threshold: format!("{threshold} (wall times: listed, never failing the command)"),
        ours: ours.clone(),
        holds,
        gate: false,
    };
    vec![
        judged(
            "fig11_cheaper",
            "the advantage in using the simplified models is large, particularly on rough ground",
            "Z_R = 0.3, V = 0.1 m/s: each reduced level's median wall time below the full model's",
            shares.iter().all(|s| s.is_some_and(|s| s < 1.0)),
        ),
        judged(
            "fig11_shares",
            "at Z_R = 0.3, V = 0.1 m/s: simplified ≈ 70 %, linearized ≈ 58 %, quasi-static ≈ 15 % of the full model's time",
            &format!(
                "each share within {:.0} percentage points of the paper's",
                100.0 * FIG11_SHARE_TOLERANCE
            ),
            shares
                .iter()
                .zip(FIG11_PAPER_SHARES)
                .all(|(s, p)| s.is_some_and(|s| (s - p).abs() <= FIG11_SHARE_TOLERANCE)),
        ),
    ]
}

/// Fig. 12's claims on its own case (Z_R = 0.1, seed 1): the simplified and
/// linearized levels quite close to the full model, the quasi-static one
/// differing most.
fn fig12_claims(l: &Levels) -> Result<Vec<Judged>, CliError> {
    let full = &l.full.0;
    let dev = |c: &Case| -> Result<Option<[f64; 6]>, CliError> {
        Ok(if c.summary.complete && full.summary.complete {
            Some(deviations(&full.csv, &c.csv)?)
        } else {
            None
        })
    };
    let (sim, lin, qs) = (
        dev(&l.simplified.0)?,
        dev(&l.linearized.0)?,
        dev(&l.quasi_static.0)?,
    );
    let show = |name: &str, d: Option<[f64; 6]>| match d {
        Some(d) => format!(
            "{name}: ΔX {:.3}, ΔY {:.3}, ΔZ {:.3} m, Δφ {:.2}°, Δθ {:.2}°, Δψ {:.2}°",
            d[0], d[1], d[2], d[3], d[4], d[5]
        ),
        None => format!("{name}: stopped"),
    };
    let close = |d: Option<[f64; 6]>| {
        d.is_some_and(|d| d[0].max(d[1]) <= CLOSE_M && d[3].max(d[4]).max(d[5]) <= CLOSE_DEG)
    };
    // Z, roll and pitch: the quantities the quasi-static level computes
    // (its X, Y and yaw are the full model's, imposed).
    let larger = match (qs, sim, lin) {
        (Some(q), Some(s), Some(l)) => [2, 3, 4].iter().all(|&k| q[k] > s[k].max(l[k])),
        _ => false,
    };
    let case =
        format!("Example 2, Z_R = {FIG12_ROUGHNESS}, V = 0.1 m/s, Δτ = 0.2 N·m, seed {SEED}");
    Ok(vec![
        Judged {
            id: "fig12_close_zr0.1".into(),
            figure: "Fig. 12".into(),
            paper: "the simplified and linearized levels' results are quite close to the full model's (Z_R = 0.1)".into(),
            threshold: format!(
                "{case}: each level completes, its largest deviation from the full model within {CLOSE_M} m in X and Y and within {CLOSE_DEG}° in roll, pitch and yaw"
            ),
            ours: format!("{}; {}", show("simplified", sim), show("linearized", lin)),
            holds: close(sim) && close(lin),
            gate: true,
        },
        Judged {
            id: "fig12_quasi_static_larger".into(),
            figure: "Fig. 12".into(),
            paper: "only the quasi-static model shows larger differences".into(),
            threshold: format!(
                "{case}: the quasi-static level's largest deviation in Z, in roll and in pitch each above both other reduced levels'"
            ),
            ours: show("quasi-static", qs),
            holds: larger,
            gate: true,
        },
    ])
}

/// Fig. 12: the reduced levels against the full one.
fn fig12(v: &mut Values, work: &Path, figs: &Path, l: &Levels) -> Result<(), CliError> {
    let names = ["X", "Y", "Z", "phi", "theta", "psi"];
    let mut t = String::from(
        "| level | max ΔX [m] | max ΔY [m] | max ΔZ [m] | max Δφ [°] | max Δθ [°] | max Δψ [°] |\n|---|---|---|---|---|---|---|\n",
    );
    // The linearized level's variant that keeps R exact (docs/FIDELITY.md),
    // on the same case, for the table only.
    let exact_rotation = run_case(
        "swing4",
        &slip(
            &CHOSEN.terrain(FIG12_ROUGHNESS, SEED),
            FIG11_SPEED,
            FIG11_DELTA_TAU,
            calibration::FULL.fig11,
            "fidelity = \"linearized_exact_rotation\"",
        ),
        &work.join("fig12/linearized_exact_rotation.csv"),
    )?;
    let all = [
        ("full", &l.full.0),
        ("simplified", &l.simplified.0),
        ("linearized", &l.linearized.0),
        ("quasi-static", &l.quasi_static.0),
    ];
    let table = [
        ("simplified", &l.simplified.0),
        ("linearized (the paper's)", &l.linearized.0),
        ("linearized, exact rotation", &exact_rotation),
        ("quasi-static", &l.quasi_static.0),
    ];
    for (label, case) in table {
        let _ = write!(t, "| {label} |");
        for d in deviations(&l.full.0.csv, &case.csv)? {
            let _ = write!(t, " {d:.3} |");
        }
        t.push('\n');
    }
    for (k, name) in names.iter().enumerate() {
        let deg = k >= 3;
        let mut ser = Vec::new();
        for (label, case) in all {
            let c = columns(&case.csv, &["t", name])?;
            let points = c[0]
                .iter()
                .zip(&c[1])
                .map(|(t, v)| (*t, if deg { v.to_degrees() } else { *v }))
                .collect();
            ser.push(series(label, points, false));
        }
        let unit = if deg { "[°]" } else { "[m]" };
        chart(
            &figs.join(format!("fig12_{name}")),
            &format!("Fig. 12 — {name}"),
            "t [s]",
            &format!("{name} {unit}"),
            ser,
        )?;
    }
    v.set("fig12_table", t);
    Ok(())
}

/// Figs. 13–14: Example 2, Δτ = 0.1 N·m, Z_R = 0.2.
fn fig13(v: &mut Values, work: &Path, figs: &Path) -> Result<(), CliError> {
    let case = run_case(
        "swing4",
        &slip(&CHOSEN.terrain(0.2, SEED), 0.05, 0.1, 40.0, ""),
        &work.join("fig13/run.csv"),
    )?;
    plot_case(&case, "swing4", &figs.join("fig13"))?;
    v.num("fig13_roll", case.summary.max_roll_deg, 1);
    v.num("fig13_pitch", case.summary.max_pitch_deg, 1);
    Ok(())
}

fn slide_cell(s: &Summary) -> String {
    match s.slide.as_ref().and_then(|x| x.sudden.as_ref()) {
        Some(x) => format!(
            "at t = {:.1} s, {:.2} m from the start: yaw {:+.1}° in 2 s, axle {} of {} sideways at {:+.3} m/s",
            x.t,
            x.distance_m,
            x.yaw_change_deg,
            x.axle + 1,
            s.slide.as_ref().map_or(0, |sl| sl.axles.len()),
            x.lateral_speed_m_s
        ),
        None => "none".into(),
    }
}

/// Figs. 15–16: passive against active over the seeds; the plots for the
/// first seed whose passive rover slides.
fn fig15(
    v: &mut Values,
    figs: &Path,
    chosen: &[(Record, Case)],
    outcome: &Outcome,
) -> Result<(), CliError> {
    let mut t = String::from(
        "| seed | suspension | status | max roll [°] | max pitch [°] | largest yaw-rate excursion [°/s] | largest axle sideways speed, front / rear [m/s] | sudden slide |\n|---|---|---|---|---|---|---|---|\n",
    );
    for seed in SEEDS {
        for label in ["passive", "active"] {
            let Some((_, c)) = chosen
                .iter()
                .find(|(r, _)| r.seed == seed && r.case == format!("fig15_{label}"))
            else {
                continue;
            };
            let s = &c.summary;
            let (excursion, axles) = s.slide.as_ref().map_or(("—".into(), "—".into()), |x| {
                (
                    format!("{:.2}", x.max_yaw_rate_excursion_deg_s),
                    x.axles
                        .iter()
                        .map(|a| format!("{:+.3}", a.max_lateral_speed_m_s))
                        .collect::<Vec<_>>()
                        .join(" / "),
                )
            });
            let _ = writeln!(
                t,
                "| {seed} | {label} | {:?} | {:.2} | {:.2} | {excursion} | {axles} | {} |",
                s.status,
                s.max_roll_deg,
                s.max_pitch_deg,
                slide_cell(s)
            );
        }
    }
    let slid = outcome.slides("fig15_passive");
    let seed = slid.first().map_or(SEED, |s| s.0);
    v.set("fig15_table", t);
    v.set("fig15_seed", seed.to_string());
    v.set(
        "fig15_seed_why",
        if slid.is_empty() {
            "no passive run slides; the first seed".to_string()
        } else {
            "the first seed whose passive rover slides".to_string()
        },
    );
    let pick = |label: &str| {
        chosen
            .iter()
            .find(|(r, _)| r.seed == seed && r.case == format!("fig15_{label}"))
            .map(|(_, c)| c)
            .ok_or_else(|| other("no Fig. 15 run"))
    };
    let (passive, active) = (pick("passive")?, pick("active")?);
    for (label, case) in [("passive", passive), ("active", active)] {
        plot_case(case, "swing4", &figs.join(format!("fig16_{label}")))?;
    }
    fig15_panels(figs, passive, active)
}

/// One panel of Fig. 15: CSV columns against time.
struct Panel {
    stem: &'static str,
    title: &'static str,
    columns: &'static [&'static str],
    /// Drawn in degrees (angles in the CSV are radians).
    degrees: bool,
    y_label: &'static str,
}

/// Fig. 15 (a)–(d): G's position, the attitude, the swing arms and the
/// active suspension's commanded spring neutrals.
fn fig15_panels(figs: &Path, passive: &Case, active: &Case) -> Result<(), CliError> {
    let panel = |stem, title, columns: &'static [&'static str], degrees, y_label| Panel {
        stem,
        title,
        columns,
        degrees,
        y_label,
    };
    let panels = [
        panel(
            "fig15_position",
            "Fig. 15 (a) — position of G",
            &["X", "Y", "Z"],
            false,
            "position [m]",
        ),
        panel(
            "fig15_attitude",
            "Fig. 15 (b) — roll, pitch and yaw",
            &["phi", "theta", "psi"],
            true,
            "angle [°]",
        ),
        panel(
            "fig15_arms",
            "Fig. 15 (c) — swing-arm angles",
            &["y1", "y2", "y3", "y4"],
            true,
            "angle [°]",
        ),
        panel(
            "fig15_control",
            "Fig. 15 (d) — commanded spring neutrals y0 (active)",
            &["y0_1", "y0_2", "y0_3", "y0_4"],
            true,
            "angle [°]",
        ),
    ];
    for Panel {
        stem,
        title,
        columns: names,
        degrees: deg,
        y_label,
    } in panels
    {
        let mut ser = Vec::new();
        let cases: &[(&str, &Case)] = if stem == "fig15_control" {
            &[("active", active)]
        } else {
            &[("passive", passive), ("active", active)]
        };
        for (label, case) in cases {
            let mut wanted = vec!["t"];
            wanted.extend_from_slice(names);
            let c = columns(&case.csv, &wanted)?;
            for (k, name) in names.iter().enumerate() {
                let points = c[0]
                    .iter()
                    .zip(&c[k + 1])
                    .map(|(t, v)| (*t, if deg { v.to_degrees() } else { *v }))
                    .collect();
                ser.push(series(&format!("{name}, {label}"), points, false));
            }
        }
        chart(&figs.join(stem), title, "t [s]", y_label, ser)?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_single_track_model_ignores_walking_speed_and_turns_kinematically_when_steered_gently() {
        let spec = load_rover("exomars", None).unwrap();
        let b = handling::SingleTrack::new(&spec.model);
        assert_eq!(b.axles.len(), 3);
        for d in [2.0f64, 10.0, 20.0] {
            let d = d.to_radians();
            // At 0.05 m/s the lateral acceleration is negligible: the
            // radius is that of a rover ten times slower.
            let r = b.radius(d, 0.05).unwrap();
            let crawl = b.radius(d, 0.005).unwrap();
            assert!((r / crawl - 1.0).abs() < 1e-3, "{r} {crawl}");
        }
        // At walking speed the equivalent wheels roll without slip: the
        // turn is the kinematic one, gently steered or not.
        for d in [2.0f64, 20.0, 30.0] {
            let (_, rk) = b.ackermann(d.to_radians());
            let r = b.radius(d.to_radians(), 0.005).unwrap();
            assert!((r / rk - 1.0).abs() < 1e-6, "δ₁ {d}°: R {r}, R_k {rk}");
        }
        // Faster, the centripetal force needs slip: the radius changes.
        let d = 10f64.to_radians();
        let slow = b.radius(d, 0.05).unwrap();
        let fast = b.radius(d, 2.0).unwrap();
        assert!((fast - slow).abs() > 0.01 * slow, "{slow} {fast}");
    }
}
