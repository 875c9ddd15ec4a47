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
    /// Length of G's horizontal path after settling \[m\].
    pub distance_m: f64,
    /// Distance the speed command asked for after settling, `∫|V| dt` \[m\]
    /// (0 without a speed loop).
    pub commanded_distance_m: f64,
    /// Set when the rover made almost none of the way its speed command
    /// asked for at the end of the run (see [`Stall`]).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub stalled: Option<Stall>,
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

/// A rover that no longer follows its speed command: over the last
/// [`STALL_WINDOW`] seconds of the run (or all of it after settling, if
/// shorter) G's net horizontal displacement was below [`STALL_FRACTION`] of
/// the distance the command asked for, and that distance was at least
/// [`STALL_MIN_DISTANCE`]. Typically wheels against an obstacle or the
/// drive torque limit on a slope: the run itself is valid, but it is not
/// the traverse its scenario describes.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Stall {
    /// Length of the window \[s\].
    pub window_s: f64,
    /// G's net horizontal displacement over the window \[m\].
    pub moved_m: f64,
    /// What the speed command asked for over the window \[m\].
    pub commanded_m: f64,
    /// Each motor's torque at the last output [N·m]: at its limit, the
    /// rover is against something it cannot climb; well below, the speed
    /// loop asks too little.
    pub final_torques: Vec<f64>,
}

/// Window over which a stall is judged \[s\].
pub const STALL_WINDOW: f64 = 10.0;
/// A rover covering less than this fraction of its commanded distance stalled.
pub const STALL_FRACTION: f64 = 0.1;
/// Commanded distances below this are too short to judge \[m\].
pub const STALL_MIN_DISTANCE: f64 = 0.01;

/// The stall over the end of a run from its rows after settling: times,
/// horizontal positions of G and speed setpoints.
fn stall(
    times: &[f64],
    path: &[[f64; 2]],
    setpoints: &[f64],
    final_torques: Vec<f64>,
) -> Option<Stall> {
    let end = *times.last()?;
    let from = times.partition_point(|&t| t < end - STALL_WINDOW);
    let commanded = commanded_distance(&times[from..], &setpoints[from..]);
    let (a, b) = (path[from], path[path.len() - 1]);
    let moved = (b[0] - a[0]).hypot(b[1] - a[1]);
    (commanded >= STALL_MIN_DISTANCE && moved < STALL_FRACTION * commanded).then(|| Stall {
        window_s: end - times[from],
        moved_m: moved,
        commanded_m: commanded,
        final_torques,
    })
}

/// `∫|V| dt` by the trapezoidal rule over output rows.
fn commanded_distance(times: &[f64], setpoints: &[f64]) -> f64 {
    let (t, v) = (times, setpoints);
    (1..t.len())
        .map(|i| 0.5 * (v[i - 1].abs() + v[i].abs()) * (t[i] - t[i - 1]))
        .sum()
}

fn as_map<S: serde::Serializer>(v: &[(String, f64)], s: S) -> Result<S::Ok, S::Error> {
    s.collect_map(v.iter().map(|(k, x)| (k, x)))
}

/// What a run's output rows add up to, kept as they are written (by both
/// the ODE runs and the quasi-static ones), then turned into a [`Summary`].
#[derive(Clone, Debug, Default)]
pub struct RunLog {
    settle: f64,
    /// G's horizontal position, the time and the speed setpoint of every
    /// row after settling.
    path: Vec<[f64; 2]>,
    times: Vec<f64>,
    setpoints: Vec<f64>,
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

    /// Record a CSV row (columns of [`super::header`], the speed setpoint
    /// last) and which wheels had a deep penetration.
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
            self.times.push(row[0]);
            self.setpoints.push(row.last().copied().unwrap_or(0.0));
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
            distance_m: self
                .path
                .windows(2)
                .map(|p| (p[1][0] - p[0][0]).hypot(p[1][1] - p[0][1]))
                .sum(),
            commanded_distance_m: commanded_distance(&self.times, &self.setpoints),
            stalled: stall(
                &self.times,
                &self.path,
                &self.setpoints,
                header
                    .iter()
                    .zip(&self.last)
                    .filter(|(name, _)| name.starts_with("tau"))
                    .map(|(_, v)| *v)
                    .collect(),
            ),
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

#[cfg(test)]
mod tests {
    use super::*;

    /// Rows every 0.1 s over `seconds`: G at `x(t)`, setpoint `v`.
    fn rows(seconds: f64, v: f64, x: impl Fn(f64) -> f64) -> (Vec<f64>, Vec<[f64; 2]>, Vec<f64>) {
        let n = (seconds * 10.0).round() as usize;
        let t: Vec<f64> = (0..=n).map(|i| i as f64 * 0.1).collect();
        let p = t.iter().map(|&t| [x(t), 0.0]).collect();
        (t, p, vec![v; n + 1])
    }

    #[test]
    fn a_rover_following_its_command_has_not_stalled() {
        let (t, p, v) = rows(30.0, 0.2, |t| 0.2 * t);
        assert_eq!(stall(&t, &p, &v, vec![]), None);
        assert!((commanded_distance(&t, &v) - 6.0).abs() < 1e-9);
    }

    #[test]
    fn a_rover_stuck_at_the_end_has_stalled_over_the_last_window() {
        // Drives 20 s, then stops dead for the last 10 s.
        let (t, p, v) = rows(30.0, 0.2, |t| 0.2 * t.min(20.0));
        let s = stall(&t, &p, &v, vec![]).expect("stalled");
        assert!((s.window_s - STALL_WINDOW).abs() < 1e-9);
        assert!((s.commanded_m - 2.0).abs() < 1e-9);
        assert!(s.moved_m < 1e-12);
        // Still crawling at 9 % of the command: stalled; at 11 %: not.
        for (share, stalled) in [(0.09, true), (0.11, false)] {
            let (t, p, v) = rows(30.0, 0.2, |t| share * 0.2 * t);
            assert_eq!(stall(&t, &p, &v, vec![]).is_some(), stalled, "{share}");
        }
    }

    #[test]
    fn a_rover_without_speed_command_or_with_a_short_run_is_judged_fairly() {
        // Parked on purpose: nothing was asked, nothing is reported.
        let (t, p, v) = rows(30.0, 0.0, |_| 0.0);
        assert_eq!(stall(&t, &p, &v, vec![]), None);
        // A run shorter than the window is judged over all of it.
        let (t, p, v) = rows(4.0, 0.2, |_| 0.0);
        let s = stall(&t, &p, &v, vec![]).expect("stalled");
        assert!((s.window_s - 4.0).abs() < 1e-9 && (s.commanded_m - 0.8).abs() < 1e-9);
        // Too little asked to judge (under 1 cm).
        let (t, p, v) = rows(4.0, 0.002, |_| 0.0);
        assert_eq!(stall(&t, &p, &v, vec![]), None);
        // No rows after settling.
        assert_eq!(stall(&[], &[], &[], vec![]), None);
    }
}
