//! The runs of the reproduction: scenario texts, one run, its CSV columns
//! and the circle fitted to the rough part of its path.

use std::path::{Path, PathBuf};
use std::sync::atomic::AtomicBool;

use rover_scenario::output::{Circle, Status, Summary, fit_circle};
use rover_scenario::prepare::Prepared;

use crate::error::CliError;

/// One run: its summary and its CSV.
pub struct Case {
    pub summary: Summary,
    pub csv: PathBuf,
}

/// A figure that cannot be made, or a claim that no longer holds.
pub fn other(e: impl std::fmt::Display) -> CliError {
    CliError::Reproduce(e.to_string())
}

/// Settling time of every run \[s\] (the paper's 6 s).
pub const SETTLE: f64 = 6.0;

/// Radius of the flat start patch around the start of G \[m\]: the front
/// wheels (0.33 m ahead of G on Example 1, 0.29 m on Example 2) roll 0.3 m
/// on flat ground before the terrain starts, as in the paper.
pub const PATCH_RADIUS: f64 = 0.63;

/// Width of the blend from the flat patch into the field \[m\].
pub const PATCH_BLEND: f64 = 0.15;

/// The random field's free scales: node amplitude and node spacing
/// (docs/TERRAIN.md, the random field).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Field {
    /// Node values uniform in ±`amplitude` before Z_R \[m\].
    pub amplitude: f64,
    /// Node spacing, about 1.28 correlation lengths \[m\].
    pub spacing: f64,
}

impl Field {
    /// The `[terrain]` table at roughness `z_r`, seed `seed` (flat at 0).
    pub fn terrain(&self, z_r: f64, seed: u64) -> String {
        if z_r == 0.0 {
            return "[terrain]\nkind = \"flat\"\n".into();
        }
        format!(
            "[terrain]\nkind = \"random\"\nz_r = {z_r}\nseed = {seed}\nnode_amplitude = {}\nnode_spacing = {}\n\
             patch_radius = {PATCH_RADIUS}\npatch_blend = {PATCH_BLEND}\n",
            self.amplitude, self.spacing
        )
    }
}

/// Integrator of every run: BDF orders 1–2 (the active law restarts the
/// integrator every 0.1 s; higher orders stalled there).
const INTEGRATOR: &str = "[integrator.bdf]\nrtol = 1e-6\natol = 1e-8\nmax_order = 2\n";

/// Example 1 (ExoMars), Ackermann steering with the front-left wheel at
/// `delta1_deg`, PI speed loop, for `duration` seconds.
pub fn ackermann(terrain: &str, speed: f64, delta1_deg: f64, duration: f64) -> String {
    format!(
        "duration = {duration}\nsettle = {SETTLE}\noutput_rate = 10.0\n{terrain}\
         [control.speed]\nspeed = {speed}\nkp = 10.0\nki = 5.0\n\
         [control.steering]\nkind = \"ackermann\"\nfront_left_deg = {delta1_deg}\n{INTEGRATOR}"
    )
}

/// Example 2 (swing arms), slip steering with `delta_tau`, P speed loop;
/// `extra` goes at the top level.
pub fn slip(terrain: &str, speed: f64, delta_tau: f64, duration: f64, extra: &str) -> String {
    format!(
        "duration = {duration}\nsettle = {SETTLE}\noutput_rate = 10.0\n{extra}\n{terrain}\
         [control.speed]\nspeed = {speed}\nkp = 10.0\n\
         [control.steering]\nkind = \"slip\"\ndelta_tau = {delta_tau}\n{INTEGRATOR}"
    )
}

/// The active suspension of Figs. 15–16: the model-based leveling law
/// (ours; its gains derived from the rover, docs/MODEL.md §8), updated
/// every 0.1 s as the paper's.
pub const ACTIVE: &str = "\n[control.active_suspension]\nlaw = \"leveling\"\nsample_time = 0.1\n";

/// Run `rover` on the scenario text, CSV into `csv`.
pub fn run_case(rover: &str, text: &str, csv: &Path) -> Result<Case, CliError> {
    let base = csv.parent().unwrap_or(Path::new("."));
    let prepared = Prepared::from_text(Some(rover), text, csv, base)?;
    rover_files::OutputDir::create(base).map_err(|e| CliError::io(base, "create the folder", e))?;
    let file = std::io::BufWriter::new(
        rover_files::create_fresh(csv).map_err(|e| CliError::io(csv, "create the CSV", e))?,
    );
    // The generic plant for every rover and level: the reproduction's
    // figures do not depend on which rovers have a generated plant.
    let summary = prepared.run(true, file, &AtomicBool::new(false), |_| {})?;
    Ok(Case {
        summary,
        csv: csv.to_path_buf(),
    })
}

/// The named columns of a run's CSV (a cell that is not a number is
/// skipped with its row).
pub fn columns(csv: &Path, names: &[&str]) -> Result<Vec<Vec<f64>>, CliError> {
    let text = rover_files::read_text(csv, rover_files::Limit::Data)
        .map_err(|e| other(format!("{}: {e}", csv.display())))?;
    let mut lines = text.lines();
    let header: Vec<&str> = lines.next().unwrap_or("").split(',').collect();
    let idx: Vec<usize> = names
        .iter()
        .map(|n| {
            header
                .iter()
                .position(|h| h == n)
                .ok_or_else(|| other(format!("{}: no column {n}", csv.display())))
        })
        .collect::<Result<_, _>>()?;
    let mut out = vec![Vec::new(); names.len()];
    for l in lines {
        let v: Vec<&str> = l.split(',').collect();
        let row: Option<Vec<f64>> = idx
            .iter()
            .map(|&i| v.get(i).and_then(|s| s.parse().ok()))
            .collect();
        if let Some(row) = row {
            for (o, x) in out.iter_mut().zip(row) {
                o.push(x);
            }
        }
    }
    Ok(out)
}

/// The circle fitted to G's path on the rough part only: after settling,
/// with G beyond the flat patch and its blend.
pub fn rough_circle(csv: &Path) -> Result<Option<Circle>, CliError> {
    let c = columns(csv, &["t", "X", "Y"])?;
    let points: Vec<[f64; 2]> = (0..c[0].len())
        .filter(|&k| c[0][k] >= SETTLE && c[1][k].hypot(c[2][k]) >= PATCH_RADIUS + PATCH_BLEND)
        .map(|k| [c[1][k], c[2][k]])
        .collect();
    Ok(fit_circle(&points))
}

/// R/R_k of a completed Ackermann run, R fitted on the rough part.
pub fn rough_ratio(case: &Case) -> Result<Option<f64>, CliError> {
    let s = &case.summary;
    if s.status != Status::Completed {
        return Ok(None);
    }
    let (Some(rk), Some(c)) = (s.kinematic_radius, rough_circle(&case.csv)?) else {
        return Ok(None);
    };
    Ok(Some(c.radius / rk))
}

/// The largest deviation of a run from the full model's, row by row over
/// the rows both have: X, Y, Z \[m\], roll, pitch, yaw \[deg\].
pub fn deviations(full: &Path, other_csv: &Path) -> Result<[f64; 6], CliError> {
    const NAMES: [&str; 6] = ["X", "Y", "Z", "phi", "theta", "psi"];
    let base = columns(full, &NAMES)?;
    let run = columns(other_csv, &NAMES)?;
    let mut out = [0.0; 6];
    for (k, o) in out.iter_mut().enumerate() {
        let d = base[k]
            .iter()
            .zip(&run[k])
            .map(|(a, b)| (a - b).abs())
            .fold(0.0, f64::max);
        *o = if k >= 3 { d.to_degrees() } else { d };
    }
    Ok(out)
}
