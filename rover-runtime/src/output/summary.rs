//! The run summary (`summary.json`).

use serde::Serialize;

use super::Circle;

/// How the run ended.
#[derive(Clone, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Status {
    /// The end time was reached: the outputs are complete.
    Completed,
    /// Interrupted by the user: the CSV holds what was computed (partial).
    Interrupted,
    /// Stopped by an error (roll-over, divergence, off the map): the CSV
    /// holds the rows up to the failure (incomplete).
    Failed,
}

/// Everything a rover engineer wants to know about a run at a glance.
#[derive(Clone, Debug, Serialize)]
pub struct Summary {
    /// The rover's name.
    pub rover: String,
    /// How the run ended.
    pub status: Status,
    /// The error, when it failed.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub error: Option<String>,
    /// Whether the CSV covers the whole requested duration.
    pub complete: bool,
    /// Requested duration \[s\].
    pub duration: f64,
    /// Time reached \[s\].
    pub t_end: f64,
    /// Final state, by CSV column name (a JSON object in column order).
    #[serde(serialize_with = "as_map")]
    pub final_state: Vec<(String, f64)>,
    /// Largest |roll| at output instants \[deg\].
    pub max_roll_deg: f64,
    /// Largest |pitch| at output instants \[deg\].
    pub max_pitch_deg: f64,
    /// Circle fitted to G's path after settling.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub turning_circle: Option<Circle>,
    /// Kinematic turning radius R_k of the Ackermann command \[m\].
    #[serde(skip_serializing_if = "Option::is_none")]
    pub kinematic_radius: Option<f64>,
    /// Wheels (1-based) that had their whole lower half below ground at some output instant.
    pub deep_penetration_wheels: Vec<usize>,
    /// Wall-clock time of the integration \[s\].
    pub wall_time_s: f64,
    /// Simulated seconds per wall-clock second.
    pub real_time_factor: f64,
    /// Integrator name.
    pub integrator: String,
    /// The plant back end: `generic`, or the generated type's name (set by the caller).
    pub plant: String,
    /// Right-hand-side evaluations.
    pub rhs_evals: u64,
    /// Accepted steps.
    pub steps: u64,
    /// Rejected steps.
    pub rejected_steps: u64,
}

fn as_map<S: serde::Serializer>(v: &[(String, f64)], s: S) -> Result<S::Ok, S::Error> {
    s.collect_map(v.iter().map(|(k, x)| (k, x)))
}

/// What a run's output rows add up to, kept as they are written (by both
/// the ODE runs and the quasi-static ones), then turned into a [`Summary`].
#[derive(Clone, Debug, Default)]
pub struct RunLog {
    settle: f64,
    path: Vec<[f64; 2]>,
    last: Vec<f64>,
    max_roll: f64,
    max_pitch: f64,
    deep: Vec<bool>,
}

/// The parts of a summary the log does not know.
#[derive(Clone, Debug)]
pub struct RunEnd {
    /// The rover's name.
    pub rover: String,
    /// How the run ended.
    pub status: Status,
    /// The error or interruption, if any.
    pub error: Option<String>,
    /// Requested duration \[s\].
    pub duration: f64,
    /// Time reached \[s\].
    pub t_end: f64,
    /// Kinematic turning radius R_k, if steering kinematically \[m\].
    pub kinematic_radius: Option<f64>,
    /// Wall-clock time \[s\].
    pub wall_time_s: f64,
    /// Method name.
    pub integrator: String,
    /// Right-hand-side (or residual) evaluations.
    pub rhs_evals: u64,
    /// Accepted steps (or Newton iterations).
    pub steps: u64,
    /// Rejected steps.
    pub rejected_steps: u64,
}

impl RunLog {
    /// A log for a run whose commands start at `settle`, with `wheels` wheels.
    pub fn new(settle: f64, wheels: usize) -> Self {
        Self {
            settle,
            deep: vec![false; wheels],
            ..Self::default()
        }
    }

    /// Record a CSV row (columns of [`super::header`]) and which wheels had a
    /// deep penetration.
    pub fn record(&mut self, row: &[f64], deep: impl Iterator<Item = bool>) {
        self.last.clear();
        self.last.extend_from_slice(row);
        self.max_roll = self.max_roll.max(row[4].abs());
        self.max_pitch = self.max_pitch.max(row[5].abs());
        for (d, now) in self.deep.iter_mut().zip(deep) {
            *d |= now;
        }
        if row[0] >= self.settle {
            self.path.push([row[1], row[2]]);
        }
    }

    /// The summary, with the final state named by `header` (state columns only).
    pub fn summary(self, header: &[String], dof: usize, end: RunEnd) -> Summary {
        Summary {
            rover: end.rover,
            complete: end.status == Status::Completed,
            status: end.status,
            error: end.error,
            duration: end.duration,
            t_end: end.t_end,
            final_state: header
                .iter()
                .cloned()
                .zip(self.last.iter().copied())
                .take(1 + 2 * dof)
                .collect(),
            max_roll_deg: self.max_roll.to_degrees(),
            max_pitch_deg: self.max_pitch.to_degrees(),
            turning_circle: super::fit_circle(&self.path),
            kinematic_radius: end.kinematic_radius,
            deep_penetration_wheels: self
                .deep
                .iter()
                .enumerate()
                .filter(|(_, d)| **d)
                .map(|(i, _)| i + 1)
                .collect(),
            wall_time_s: end.wall_time_s,
            real_time_factor: if end.wall_time_s > 0.0 {
                end.t_end / end.wall_time_s
            } else {
                f64::INFINITY
            },
            integrator: end.integrator,
            plant: "generic".into(),
            rhs_evals: end.rhs_evals,
            steps: end.steps,
            rejected_steps: end.rejected_steps,
        }
    }
}
