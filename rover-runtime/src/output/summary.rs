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
    /// Requested duration [s].
    pub duration: f64,
    /// Time reached [s].
    pub t_end: f64,
    /// Final state, by CSV column name (a JSON object in column order).
    #[serde(serialize_with = "as_map")]
    pub final_state: Vec<(String, f64)>,
    /// Largest |roll| at output instants [deg].
    pub max_roll_deg: f64,
    /// Largest |pitch| at output instants [deg].
    pub max_pitch_deg: f64,
    /// Circle fitted to G's path after settling.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub turning_circle: Option<Circle>,
    /// Kinematic turning radius R_k of the Ackermann command [m].
    #[serde(skip_serializing_if = "Option::is_none")]
    pub kinematic_radius: Option<f64>,
    /// Wheels (1-based) that had their whole lower half below ground at some output instant.
    pub deep_penetration_wheels: Vec<usize>,
    /// Wall-clock time of the integration [s].
    pub wall_time_s: f64,
    /// Simulated seconds per wall-clock second.
    pub real_time_factor: f64,
    /// Integrator name.
    pub integrator: String,
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
