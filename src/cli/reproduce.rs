//! `rover reproduce`: rerun the paper's figures (MODEL.md §10) on one
//! calibrated terrain and write docs/REPRODUCTION.md with the plots, our
//! numbers beside the paper's. The prose is `reproduce/report.md`; the code
//! fills its placeholders and fails the command when a claim the
//! calibration reproduces stops holding.

mod calibration;
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
    CHOSEN, Claim, EXAMPLE1_DURATION, FIG6_ROUGHNESS, FIG7_ROUGHNESS, FIG7_SPEEDS, Outcome, Record,
    SEARCH_DELTA, SEEDS,
};
use runs::{Case, Field, ackermann, columns, other, rough_ratio, run_case, slip};
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
    /// Where the runs' CSVs go (not committed).
    #[arg(long, default_value = "out/reproduction")]
    pub work: PathBuf,
    /// Rerun the terrain search over the whole grid and store it in
    /// `<docs>/reproduction/calibration.csv` (otherwise the stored search is
    /// read and only the chosen setting is rerun).
    #[arg(long)]
    pub search: bool,
}

/// Roughness of the paper's Fig. 11 cases.
const FIG11_ROUGHNESS: [f64; 3] = [0.1, 0.3, 1.0];
/// Runs of a case whose median wall time is taken.
const TIMED_RUNS: usize = 5;
/// Steering angles of Fig. 5 \[deg\].
const FIG5_DELTAS: [f64; 6] = [2.0, 5.0, 10.0, 15.0, 20.0, 30.0];
/// Steering angles of Fig. 6 \[deg\] (the searched one among them).
const FIG6_DELTAS: [f64; 3] = [10.0, SEARCH_DELTA, 30.0];
/// Seed of the single-seed figures (8–14).
const SEED: u64 = 1;

/// Rerun every figure and write the report; an error after writing it when
/// a claim the stored search reproduces no longer holds.
pub fn reproduce(args: &ReproduceArgs) -> Result<PathBuf, CliError> {
    let started = Instant::now();
    let figs = args.docs.join("reproduction");
    rover_files::OutputDir::create(&figs)
        .map_err(|e| CliError::io(&figs, "create the folder", e))?;
    let work = &args.work;
    let mut v = Values::default();

    let chosen_runs = calibration::evaluate(CHOSEN, work)?;
    let chosen = Outcome::new(CHOSEN, chosen_runs.iter().map(|(r, _)| r.clone()).collect());
    let search = search(args, &chosen)?;
    let stored = calibration::outcomes(&search.stored);
    calibration_section(&mut v, &search.outcomes, &chosen)?;

    fig5(&mut v, work, &figs)?;
    fig6(&mut v, work, &figs, &chosen_runs)?;
    fig7(&mut v, &figs, &chosen)?;
    steer::steer_section(&mut v, work, &figs)?;
    fig8(&mut v, work, &figs)?;
    fig11_12(&mut v, work, &figs)?;
    fig13(&mut v, work, &figs)?;
    fig15(&mut v, &figs, &chosen_runs, &chosen)?;

    v.num("wall_time_s", started.elapsed().as_secs_f64(), 0);
    let out = args.docs.join("REPRODUCTION.md");
    write_whole(&out, &template::render(TEMPLATE, &v)?)?;
    check(&chosen, &stored, &search.outcomes)?;
    Ok(out)
}

/// The search's outcomes (the chosen field's from this run) and the stored
/// records it was read from.
struct Search {
    outcomes: Vec<Outcome>,
    stored: Vec<Record>,
}

/// Run the grid (with `--search`) or read the stored one; the chosen field's
/// outcome is this run's.
fn search(args: &ReproduceArgs, chosen: &Outcome) -> Result<Search, CliError> {
    let path = args.docs.join("reproduction/calibration.csv");
    let stored = if args.search {
        let mut records = Vec::new();
        for field in calibration::grid() {
            if field == CHOSEN {
                records.extend(chosen.records.iter().cloned());
            } else {
                let runs = calibration::evaluate(field, &args.work.join("search"))?;
                records.extend(runs.into_iter().map(|(r, _)| r));
            }
        }
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
    Ok(Search { outcomes, stored })
}

/// Fails when a claim the stored search reproduces on the chosen field no
/// longer holds, or when the search ranks another field first.
fn check(chosen: &Outcome, stored: &[Outcome], grid: &[Outcome]) -> Result<(), CliError> {
    let before = stored
        .iter()
        .find(|o| o.field == CHOSEN)
        .map(Outcome::claims)
        .unwrap_or_default();
    let now = chosen.claims();
    let broken: Vec<String> = before
        .iter()
        .zip(&now)
        .filter(|(b, n)| b.holds && !n.holds)
        .map(|(_, n)| format!("{} \"{}\" no longer holds: {}", n.figure, n.paper, n.ours))
        .collect();
    let mut problems = broken;
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

/// The search table, the chosen field and its claims.
fn calibration_section(v: &mut Values, grid: &[Outcome], chosen: &Outcome) -> Result<(), CliError> {
    let mut t = String::from(
        "| node amplitude a [m] | node spacing L [m] | claims held | shortfall | Fig. 6 Z_R 0.1 / 0.2 | Fig. 6 Z_R 0.5 / 1 | Fig. 7 V 0.05 / 1 | passive pitch [°] | passive slides | active roll / pitch [°] |\n|---|---|---|---|---|---|---|---|---|---|\n",
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
        let _ = writeln!(
            t,
            "| {}{mark} | {} | {held} of {} | {miss:.2} | {} / {} | {} / {} | {} / {} | {} | {} of {} | {} / {} |",
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
    v.set("claims_table", claims_table(&chosen.claims()));
    v.set("claims_missed", missed(grid));
    Ok(())
}

fn claims_table(claims: &[Claim]) -> String {
    let mut t = String::from(
        "| figure | paper | ours (mean ± sd over the seeds) | holds |\n|---|---|---|---|\n",
    );
    for c in claims {
        let _ = writeln!(
            t,
            "| {} | {} | {} | {} |",
            c.figure,
            c.paper,
            c.ours,
            if c.holds { "yes" } else { "**no**" }
        );
    }
    t
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
            let each: Vec<String> = meeting
                .iter()
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
            let _ = writeln!(out, "Met by {}.", each.join(", and by "));
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

/// Fig. 5: flat ground, the simulated radius against the kinematic one and
/// the single-track handling model's.
fn fig5(v: &mut Values, work: &Path, figs: &Path) -> Result<(), CliError> {
    let spec = load_rover("exomars", None)?;
    let bicycle = handling::SingleTrack::new(&spec.model);
    let flat = Field {
        amplitude: 0.0,
        spacing: 1.0,
    }
    .terrain(0.0, 0);
    let cases: Vec<Case> = FIG5_DELTAS
        .par_iter()
        .map(|d| {
            run_case(
                "exomars",
                &ackermann(&flat, 0.05, *d, EXAMPLE1_DURATION),
                &work.join(format!("fig5/delta{d}.csv")),
            )
        })
        .collect::<Result<_, _>>()?;
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
    // δ₁ from 2° to 30° in steps of 0.5°, as the simulated points.
    let curve: Vec<(f64, f64)> = (4..=60)
        .filter_map(|k| {
            let d = (0.5 * k as f64).to_radians();
            Some((bicycle.ackermann(d).1, bicycle.radius(d, 0.05)?))
        })
        .collect();
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

/// [`run_case`] [`TIMED_RUNS`] times: the last run and the median wall time \[s\].
fn timed(rover: &str, text: &str, csv: &Path) -> Result<(Case, f64), CliError> {
    let mut times = Vec::with_capacity(TIMED_RUNS);
    let mut last = None;
    for _ in 0..TIMED_RUNS {
        let case = run_case(rover, text, csv)?;
        times.push(case.summary.wall_time_s);
        last = Some(case);
    }
    times.sort_by(f64::total_cmp);
    let case = last.ok_or_else(|| other("no run"))?;
    Ok((case, times[TIMED_RUNS / 2]))
}

/// One Fig. 11 case: the four levels, each timed.
struct Levels {
    full: (Case, f64),
    simplified: (Case, f64),
    linearized: (Case, f64),
    quasi_static: (Case, f64),
}

fn levels(work: &Path, z: f64) -> Result<Levels, CliError> {
    let dir = work.join(format!("fig11/zr{z}"));
    let terrain = CHOSEN.terrain(z, SEED);
    let level = |name: &str, extra: &str| {
        timed(
            "swing4",
            &slip(
                &terrain,
                0.1,
                0.2,
                40.0,
                &format!("profile = true\n{extra}"),
            ),
            &dir.join(format!("{name}.csv")),
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
fn fig11_12(v: &mut Values, work: &Path, figs: &Path) -> Result<(), CliError> {
    let mut t = String::from(
        "| Z_R | full [s] | simplified | linearized | quasi-static | right-hand sides: full / simplified / linearized | full: contact / wheel law / plant / wheels / integrator and output |\n|---|---|---|---|---|---|---|\n",
    );
    let mut failures = Vec::new();
    let mut first = None;
    for z in FIG11_ROUGHNESS {
        let l = levels(work, z)?;
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
    fig12(v, figs, &l)
}

/// Fig. 12: the reduced levels against the full one.
fn fig12(v: &mut Values, figs: &Path, l: &Levels) -> Result<(), CliError> {
    let names = ["X", "Y", "Z", "phi", "theta", "psi"];
    let wanted = [&["t"], &names[..]].concat();
    let base = columns(&l.full.0.csv, &wanted)?;
    let mut t = String::from(
        "| level | max ΔX [m] | max ΔY [m] | max ΔZ [m] | max Δφ [°] | max Δθ [°] | max Δψ [°] |\n|---|---|---|---|---|---|---|\n",
    );
    let all = [
        ("full", &l.full.0),
        ("simplified", &l.simplified.0),
        ("linearized", &l.linearized.0),
        ("quasi-static", &l.quasi_static.0),
    ];
    for (label, case) in &all[1..] {
        let c = columns(&case.csv, &wanted)?;
        let _ = write!(t, "| {label} |");
        for k in 1..=6 {
            let d = base[k]
                .iter()
                .zip(&c[k])
                .map(|(a, b)| (a - b).abs())
                .fold(0.0, f64::max);
            let d = if k >= 4 { d.to_degrees() } else { d };
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
        // Gentle steering: each axle's mean angle is its wheels' angle, and
        // the turn is the kinematic one.
        let (_, rk) = b.ackermann(2f64.to_radians());
        let r = b.radius(2f64.to_radians(), 0.05).unwrap();
        assert!((r / rk - 1.0).abs() < 1e-3, "R {r}, R_k {rk}");
        // Faster, the centripetal force needs slip: the radius changes.
        let d = 10f64.to_radians();
        let slow = b.radius(d, 0.05).unwrap();
        let fast = b.radius(d, 2.0).unwrap();
        assert!((fast - slow).abs() > 0.01 * slow, "{slow} {fast}");
    }
}
