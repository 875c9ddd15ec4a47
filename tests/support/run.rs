//! Running scenarios from TOML text in tests, and reading their CSV.

use std::path::Path;
use std::sync::atomic::AtomicBool;

use rover_scenario::output::Summary;
use rover_scenario::prepare::Prepared;

/// A finished run: its summary and its CSV as columns by name.
pub struct Run {
    pub summary: Summary,
    pub header: Vec<String>,
    pub rows: Vec<Vec<f64>>,
}

impl Run {
    /// The column named `name`.
    pub fn col(&self, name: &str) -> Vec<f64> {
        let k = self
            .header
            .iter()
            .position(|h| h == name)
            .unwrap_or_else(|| panic!("no column {name}"));
        self.rows.iter().map(|r| r[k]).collect()
    }
    /// The summary's final value of state column `name`.
    pub fn final_value(&self, name: &str) -> f64 {
        self.summary
            .final_state
            .iter()
            .find(|(n, _)| n == name)
            .unwrap_or_else(|| panic!("no {name} in the final state"))
            .1
    }
    /// Rows with t ≥ t0.
    pub fn after(&self, name: &str, t0: f64) -> Vec<f64> {
        let t = self.col("t");
        self.col(name)
            .into_iter()
            .zip(t)
            .filter(|(_, t)| *t >= t0)
            .map(|(v, _)| v)
            .collect()
    }
}

/// The built-in rover a scenario's text names (`rover = "…"`).
pub fn rover_of(scenario: &str) -> String {
    scenario
        .lines()
        .find_map(|l| l.strip_prefix("rover = "))
        .map(|v| v.trim().trim_matches('"').to_owned())
        .unwrap_or_else(|| panic!("no `rover = …` line in\n{scenario}"))
}

/// Run the built-in `rover` on the scenario `toml` with the generic plant
/// at the scenario's fidelity level, as `rover simulate --generic` runs it.
pub fn run(rover: &str, toml: &str) -> Run {
    run_in(rover, toml, Path::new("."))
}

/// [`run`] with the scenario's files (commands, terrain maps) found from `dir`.
pub fn run_in(rover: &str, toml: &str, dir: &Path) -> Run {
    run_plant_in(rover, toml, dir, true)
}

/// [`run_in`] with the plant `rover simulate` runs by default (`generic =
/// false`: a built-in rover's generated plant, with its exact Jacobian) or
/// the generic one.
pub fn run_plant_in(rover: &str, toml: &str, dir: &Path, generic: bool) -> Run {
    let prepared = Prepared::from_text(Some(rover), toml, &dir.join("test.toml"), dir)
        .unwrap_or_else(|e| panic!("{e}"));
    let mut csv = Vec::new();
    let stop = AtomicBool::new(false);
    let summary = prepared
        .run(generic, &mut csv, &stop, |_| {})
        .unwrap_or_else(|e| panic!("{e}"));
    let text = String::from_utf8(csv).unwrap();
    let mut lines = text.lines();
    let header = lines.next().unwrap().split(',').map(String::from).collect();
    let rows = lines
        .map(|l| l.split(',').map(|v| v.parse().unwrap()).collect())
        .collect();
    Run {
        summary,
        header,
        rows,
    }
}
