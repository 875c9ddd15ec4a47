//! Fig. 7's dependence on the steer characteristic: Example 1 and copies
//! of it with a different understeer gradient (the front or rear wheels'
//! cornering stiffness changed, the centre of mass moved along x), turning
//! at δ₁ = 20° on flat ground at Fig. 7's speeds, each against the
//! single-track model of the same variant (the model of Fig. 5).

use std::fmt::Write as _;
use std::path::Path;

use rayon::prelude::*;
use rover_scenario::output::Status;

use super::calibration::{EXAMPLE1_DURATION, FIG7_SPEEDS};
use super::handling::SingleTrack;
use super::runs::{Field, ackermann, other, run_case};
use super::{chart, fmt_opt, series};
use crate::error::CliError;

/// The front-left wheel's steering angle of the runs \[deg\].
pub const DELTA1_DEG: f64 = 20.0;

/// A copy of Example 1 with another steer characteristic.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Variant {
    /// Its name in the table.
    pub name: &'static str,
    /// The front (steering) wheels' cornering stiffness over the rest's.
    pub front_stiffness: f64,
    /// The rear (steering) wheels' cornering stiffness over the rest's.
    pub rear_stiffness: f64,
    /// How far the centre of mass moves forward \[m\] (the suspension
    /// pivots move back by as much in body axes).
    pub shift_forward: f64,
}

/// Example 1 and four variants about it.
pub const VARIANTS: [Variant; 5] = [
    Variant {
        name: "Example 1",
        front_stiffness: 1.0,
        rear_stiffness: 1.0,
        shift_forward: 0.0,
    },
    Variant {
        name: "front wheels' C × 3",
        front_stiffness: 3.0,
        rear_stiffness: 1.0,
        shift_forward: 0.0,
    },
    Variant {
        name: "rear wheels' C × 3",
        front_stiffness: 1.0,
        rear_stiffness: 3.0,
        shift_forward: 0.0,
    },
    Variant {
        name: "G 10 cm forward",
        front_stiffness: 1.0,
        rear_stiffness: 1.0,
        shift_forward: 0.1,
    },
    Variant {
        name: "G 10 cm back",
        front_stiffness: 1.0,
        rear_stiffness: 1.0,
        shift_forward: -0.1,
    },
];

impl Variant {
    /// The variant's description: models/exomars.toml with the front and
    /// rear wheels' `cornering_stiffness` set and the pivots' x moved.
    pub fn description(&self) -> Result<String, CliError> {
        let base = rover_models::builtin("exomars").ok_or_else(|| other("no exomars"))?;
        let stiffness = base_stiffness(base)?;
        let mut out = String::with_capacity(base.len() + 256);
        for line in base.lines() {
            if let Some(rest) = line.strip_prefix("pivot = [") {
                // `pivot = [x, y, z]`: x moves back as G moves forward.
                let (x, tail) = rest
                    .split_once(',')
                    .ok_or_else(|| other(format!("exomars: cannot read `{line}`")))?;
                let x: f64 = x
                    .trim()
                    .parse()
                    .map_err(|e| other(format!("exomars: `{line}`: {e}")))?;
                let _ = writeln!(out, "pivot = [{:.4},{tail}", x - self.shift_forward);
                continue;
            }
            out.push_str(line);
            out.push('\n');
            let factor = match line.trim() {
                "name = \"front_left\"" | "name = \"front_right\"" => self.front_stiffness,
                "name = \"rear_left\"" | "name = \"rear_right\"" => self.rear_stiffness,
                _ => continue,
            };
            let _ = writeln!(out, "cornering_stiffness = {}", stiffness * factor);
        }
        Ok(out)
    }

    /// The variant's single-track model.
    pub fn single_track(&self) -> Result<SingleTrack, CliError> {
        let spec = rover_spec::load_str(&self.description()?, "exomars (variant)")
            .map_err(|e| other(format!("{}: {e}", self.name)))?;
        Ok(SingleTrack::new(&spec.model))
    }
}

/// The default cornering stiffness of models/exomars.toml [N/rad].
fn base_stiffness(text: &str) -> Result<f64, CliError> {
    text.lines()
        .find_map(|l| {
            let v = l.strip_prefix("cornering_stiffness = ")?;
            v.split('#').next()?.trim().parse().ok()
        })
        .ok_or_else(|| other("exomars: no default cornering_stiffness"))
}

/// The single-track model's R/R_k of `model` at speed `v` \[m/s\], δ₁ =
/// [`DELTA1_DEG`].
pub fn single_track_ratio(model: &SingleTrack, v: f64) -> Option<f64> {
    let d = DELTA1_DEG.to_radians();
    Some(model.radius(d, v)? / model.ackermann(d).1)
}

/// Each variant's R/R_k at each speed on flat ground: simulated (R from
/// the circle fitted to G's path)
/// and by its single-track model. Descriptions and CSVs go to `dir`.
/// `None` for a run that did not complete or spun out of the turn.
#[allow(clippy::type_complexity)]
pub fn measure(
    dir: &Path,
    variants: &[Variant],
    speeds: &[f64],
) -> Result<Vec<Vec<(Option<f64>, Option<f64>)>>, CliError> {
    rover_files::OutputDir::create(dir).map_err(|e| CliError::io(dir, "create the folder", e))?;
    let flat = Field {
        amplitude: 0.0,
        spacing: 1.0,
    }
    .terrain(0.0, 0);
    let mut models = Vec::new();
    for (k, variant) in variants.iter().enumerate() {
        let path = dir.join(format!("variant{k}.toml"));
        rover_scenario::output::write_whole(&path, &variant.description()?)?;
        models.push((path, variant.single_track()?));
    }
    let jobs: Vec<(usize, f64)> = (0..variants.len())
        .flat_map(|k| speeds.iter().map(move |&s| (k, s)))
        .collect();
    let ratios: Vec<Option<f64>> = jobs
        .par_iter()
        .map(|&(k, speed)| {
            let rover = models[k].0.to_string_lossy().into_owned();
            let case = run_case(
                &rover,
                &ackermann(&flat, speed, DELTA1_DEG, EXAMPLE1_DURATION),
                &dir.join(format!("variant{k}_v{speed}.csv")),
            )?;
            let s = &case.summary;
            Ok(match (&s.status, s.kinematic_radius, &s.turning_circle) {
                // A run that lost the turn (spun out) has no radius.
                (Status::Completed, Some(rk), Some(c)) if s.runaway.is_none() => {
                    Some(c.radius / rk)
                }
                _ => None,
            })
        })
        .collect::<Result<_, CliError>>()?;
    Ok(models
        .iter()
        .enumerate()
        .map(|(k, (_, model))| {
            speeds
                .iter()
                .enumerate()
                .map(|(j, &v)| (ratios[k * speeds.len() + j], single_track_ratio(model, v)))
                .collect()
        })
        .collect())
}

/// The table and plot of [`measure`] for [`VARIANTS`] at Fig. 7's speeds:
/// `fig7_steer_table`, `fig7_steer_limit`.
pub(super) fn steer_section(
    v: &mut super::template::Values,
    work: &Path,
    figs: &Path,
) -> Result<(), CliError> {
    let rows = measure(&work.join("fig7_steer"), &VARIANTS, &FIG7_SPEEDS)?;
    let models = VARIANTS
        .iter()
        .map(Variant::single_track)
        .collect::<Result<Vec<_>, _>>()?;
    let mut t = String::from("| variant | single-track (R/R_k − 1)/V² [s²/m²] |");
    for s in FIG7_SPEEDS {
        let _ = write!(t, " V = {s} m/s |");
    }
    t.push_str("\n|---|---|");
    t.push_str(&"---|".repeat(FIG7_SPEEDS.len()));
    t.push('\n');
    let mut plotted = Vec::new();
    for (k, variant) in VARIANTS.iter().enumerate() {
        let slope = single_track_ratio(&models[k], 0.05).map(|r| (r - 1.0) / 0.05f64.powi(2));
        let _ = write!(t, "| {} | {} |", variant.name, fmt_opt(slope, 3));
        let mut sim = Vec::new();
        let mut bicycle = Vec::new();
        for (&speed, &(r, b)) in FIG7_SPEEDS.iter().zip(&rows[k]) {
            let _ = write!(t, " {} / {} |", fmt_opt(r, 3), fmt_opt(b, 3));
            sim.extend(r.map(|r| (speed, r)));
            bicycle.extend(b.map(|b| (speed, b)));
        }
        t.push('\n');
        plotted.push(series(&format!("{} (simulated)", variant.name), sim, true));
        plotted.push(series(
            &format!("{} (single-track)", variant.name),
            bicycle,
            false,
        ));
    }
    chart(
        &figs.join("fig7_steer"),
        &format!("Fig. 7 — R/R_k against speed by steer characteristic, flat, δ₁ = {DELTA1_DEG}°"),
        "V [m/s]",
        "R/R_k",
        plotted,
    )?;
    v.set("fig7_steer_table", t);
    // The lateral acceleration at the kinematic radius over μ·g at the
    // fastest speed: beyond 1 no tyre law holds the turn.
    let spec = rover_spec::load_str(&VARIANTS[0].description()?, "exomars")
        .map_err(|e| other(e.to_string()))?;
    let rk = models[0].ackermann(DELTA1_DEG.to_radians()).1;
    let mu = spec.model.wheels[0].mu_y;
    let fastest = FIG7_SPEEDS[FIG7_SPEEDS.len() - 1];
    v.num(
        "fig7_steer_limit",
        fastest * fastest / rk / (mu * spec.model.gravity),
        2,
    );
    Ok(())
}
