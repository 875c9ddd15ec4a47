//! The run summary (`summary.json`).

use serde::Serialize;

use super::Circle;
use super::slide::{Slide, SlideTrack, slide};

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
    /// Stopped on a soil because the rover could not advance (its wheels
    /// slipping above 0.95 for 5 s, or one sunk past half its radius): the
    /// CSV holds the rows up to then (incomplete), the error says when,
    /// where and which wheels.
    Embedded,
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
    /// Set when the rover turned or drove far faster than its commands ask
    /// (see [`Runaway`]).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub runaway: Option<Runaway>,
    /// On a soil, each wheel's slip and sinkage after settling.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub soil: Option<Vec<WheelSoil>>,
    /// On ground that keeps the wheels' ruts: the deepest, the area
    /// touched, the map's size and the grid written of it.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub ruts: Option<super::RutSummary>,
    /// The ruts at the end of the run, for the files written beside the
    /// CSV (`ruts.csv`, `ruts.png`, `ground.csv`; [`super::RutGrid::files`]);
    /// not part of `summary.json`.
    #[serde(skip)]
    pub rut_grid: Option<super::RutGrid>,
    /// Sideways slides after settling: the yaw-rate excursion, each axle's
    /// sideways speed and the first sudden slide (dynamic runs).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub slide: Option<Slide>,
    /// How far G strayed from the path a heading hold follows (a line or
    /// waypoints), at output instants after settling (set by the caller).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub path_deviation: Option<PathDeviation>,
    /// Wall-clock time of the integration \[s\].
    pub wall_time_s: f64,
    /// Simulated seconds per wall-clock second.
    pub real_time_factor: f64,
    /// Integrator name.
    pub integrator: String,
    /// The plant that ran: `generic` (with its level when reduced), or
    /// `generated (<type path>)` ([`plant_label`]).
    pub plant: String,
    /// Right-hand-side evaluations.
    pub rhs_evals: u64,
    /// Accepted steps.
    pub steps: u64,
    /// Rejected steps.
    pub rejected_steps: u64,
    /// Jacobian evaluations (implicit integrators; each by finite
    /// differences costs one right-hand side per state component, counted
    /// in `rhs_evals` too).
    pub jacobian_evals: u64,
    /// LU factorizations of the Newton iteration matrix (implicit
    /// integrators).
    pub lu_decompositions: u64,
    /// Where the wall time went, when the scenario asked (`profile = true`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub profile: Option<rover_runtime::sim::Profile>,
}

/// One wheel on a soil, over the output instants after settling.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct WheelSoil {
    /// The wheel (1-based, the description's order).
    pub wheel: usize,
    /// Mean slip.
    pub mean_slip: f64,
    /// Largest slip.
    pub peak_slip: f64,
    /// Mean sinkage \[m\].
    pub mean_sinkage_m: f64,
    /// Largest sinkage \[m\].
    pub peak_sinkage_m: f64,
}

/// G's distance from a heading hold's path at output instants after
/// settling.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct PathDeviation {
    /// Largest distance \[m\].
    pub max_m: f64,
    /// Root mean square \[m\].
    pub rms_m: f64,
    /// Distance at the last output instant \[m\].
    pub final_m: f64,
}

/// A rover that no longer follows its speed command: over the last
/// [`STALL_WINDOW`] seconds of the run (or all of it after settling, if
/// shorter) its progress in the commanded direction, `∫ v_x dt` with v_x
/// G's forward speed in body axes, was below [`STALL_FRACTION`] of the
/// distance the command asked for, `|∫ V dt|`, and that distance was at
/// least [`STALL_MIN_DISTANCE`]. Typically wheels against an obstacle, a
/// slope beyond the motors (the rover may even slide back: negative
/// progress) or a speed loop too weak: the run itself is valid, but it is
/// not the traverse its scenario describes.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Stall {
    /// Length of the window \[s\].
    pub window_s: f64,
    /// Progress in the commanded direction over the window \[m\]
    /// (negative: the rover went back).
    pub progress_m: f64,
    /// G's net horizontal displacement over the window \[m\].
    pub moved_m: f64,
    /// What the speed command asked for over the window \[m\].
    pub commanded_m: f64,
    /// Each motor's torque at the last output [N·m]: at its limit, the
    /// rover is against something it cannot climb; well below, the speed
    /// loop asks too little.
    pub final_torques: Vec<f64>,
}

/// A rover turning or driving far beyond what its commands ask, over a
/// [`RUNAWAY_WINDOW`] after settling: its mean yaw rate above
/// `max(RUNAWAY_YAW_RATE_DEG_S, RUNAWAY_YAW_FACTOR·|V|_max/R_k)` (R_k the
/// Ackermann command's kinematic radius; no Ackermann command, only the
/// floor), or its mean horizontal speed above
/// `max(RUNAWAY_SPEED_FLOOR, RUNAWAY_SPEED_FACTOR·|V|_max)` with V the speed
/// set-point. Typically a slip-steering torque difference far beyond what
/// turning the rover needs, on motors with no speed limit (no
/// `no_load_speed`): the run is valid, but the rover is spinning out, not
/// turning (docs/CLI.md, sizing Δτ).
///
/// The bounds: no rover's steering asks for half a turn a second (real
/// skid-steered rovers turn at a few degrees a second; of the shipped
/// scenarios a heading hold pivoting at a waypoint's corner turns fastest,
/// about 100 °/s over a second, a runaway Δτ of 15 % of the motors' limit
/// on a 20 kg rover over 400 °/s), and an Ackermann turn at the set-point
/// yaws at V/R_k; a speed loop holds the set-point to within tens of
/// percent, and a rover without one (V = 0) settling, rolling off a bump
/// or under open-loop torques stays below a metre a second (the shipped
/// scenarios below 0.45 m/s).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Runaway {
    /// When the first window over a bound ended \[s\].
    pub t: f64,
    /// The largest mean yaw rate over a window, in magnitude [deg/s].
    pub yaw_rate_deg_s: f64,
    /// The largest mean horizontal speed of G over a window [m/s].
    pub speed_m_s: f64,
    /// The yaw-rate bound [deg/s].
    pub yaw_rate_bound_deg_s: f64,
    /// The speed bound [m/s].
    pub speed_bound_m_s: f64,
}

/// Window over which a runaway's yaw rate and speed are averaged \[s\]:
/// long enough that a bump's jolt does not count.
pub const RUNAWAY_WINDOW: f64 = 1.0;
/// Yaw rate no steering command asks for [deg/s]: half a turn a second.
pub const RUNAWAY_YAW_RATE_DEG_S: f64 = 180.0;
/// How far beyond an Ackermann command's yaw rate V/R_k a rover may turn.
pub const RUNAWAY_YAW_FACTOR: f64 = 3.0;
/// Speed any rover may reach without a runaway [m/s].
pub const RUNAWAY_SPEED_FLOOR: f64 = 1.0;
/// How far beyond its speed set-point a rover may drive.
pub const RUNAWAY_SPEED_FACTOR: f64 = 3.0;

/// The runaway over the rows after settling (times, yaw, G's path and
/// set-points), with an Ackermann command's kinematic radius.
fn runaway(track: &Track, yaw: &[f64], kinematic_radius: Option<f64>) -> Option<Runaway> {
    let times = track.times;
    let v_max = track.setpoints.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    let commanded_yaw = kinematic_radius
        .filter(|r| r.is_finite() && *r != 0.0)
        .map_or(0.0, |r| (v_max / r.abs()).to_degrees());
    let yaw_bound = RUNAWAY_YAW_RATE_DEG_S.max(RUNAWAY_YAW_FACTOR * commanded_yaw);
    let speed_bound = RUNAWAY_SPEED_FLOOR.max(RUNAWAY_SPEED_FACTOR * v_max);
    let (mut first, mut peak_yaw, mut peak_speed) = (None, 0.0f64, 0.0f64);
    let mut travelled = 0.0;
    // Path length from the first row to each row.
    let along: Vec<f64> = std::iter::once(0.0)
        .chain(track.path.windows(2).map(|p| {
            travelled += (p[1][0] - p[0][0]).hypot(p[1][1] - p[0][1]);
            travelled
        }))
        .collect();
    let mut j = 0;
    for i in 0..times.len() {
        while j < times.len() && times[j] < times[i] + RUNAWAY_WINDOW {
            j += 1;
        }
        if j == times.len() {
            break;
        }
        let dt = times[j] - times[i];
        let yaw_rate = ((yaw[j] - yaw[i]) / dt).abs().to_degrees();
        let speed = (along[j] - along[i]) / dt;
        peak_yaw = peak_yaw.max(yaw_rate);
        peak_speed = peak_speed.max(speed);
        if first.is_none() && (yaw_rate > yaw_bound || speed > speed_bound) {
            first = Some(times[j]);
        }
    }
    first.map(|t| Runaway {
        t,
        yaw_rate_deg_s: peak_yaw,
        speed_m_s: peak_speed,
        yaw_rate_bound_deg_s: yaw_bound,
        speed_bound_m_s: speed_bound,
    })
}

/// Window over which a stall is judged \[s\].
pub const STALL_WINDOW: f64 = 10.0;
/// A rover covering less than this fraction of its commanded distance stalled.
pub const STALL_FRACTION: f64 = 0.1;
/// Commanded distances below this are too short to judge \[m\].
pub const STALL_MIN_DISTANCE: f64 = 0.01;

/// How a run's summary names `plant`: the generic plant by its own name
/// (`generic`, with its level when reduced), any other as
/// `generated (<type path>)`.
pub fn plant_label<P: rover_dynamics::plant::Plant + ?Sized>(plant: &P) -> String {
    let name = plant.name();
    if name.starts_with("generic") {
        name.to_string()
    } else {
        format!("generated ({name})")
    }
}

/// What a run's rows after settling hold for the stall judgement.
struct Track<'a> {
    times: &'a [f64],
    /// G's horizontal position.
    path: &'a [[f64; 2]],
    /// Speed set-point V.
    setpoints: &'a [f64],
    /// G's forward speed v_x (body axes).
    forward: &'a [f64],
}

/// The stall over the end of a run.
fn stall(track: &Track, final_torques: Vec<f64>) -> Option<Stall> {
    let end = *track.times.last()?;
    let from = track.times.partition_point(|&t| t < end - STALL_WINDOW);
    let t = &track.times[from..];
    let asked = integral(t, &track.setpoints[from..], |v| v);
    let commanded = asked.abs();
    let progress = integral(t, &track.forward[from..], |v| v) * asked.signum();
    let (a, b) = (track.path[from], track.path[track.path.len() - 1]);
    (commanded >= STALL_MIN_DISTANCE && progress < STALL_FRACTION * commanded).then(|| Stall {
        window_s: end - t[0],
        progress_m: progress,
        moved_m: (b[0] - a[0]).hypot(b[1] - a[1]),
        commanded_m: commanded,
        final_torques,
    })
}

/// `∫ f(v) dt` by the trapezoidal rule over output rows.
fn integral(times: &[f64], values: &[f64], f: impl Fn(f64) -> f64) -> f64 {
    let (t, v) = (times, values);
    (1..t.len())
        .map(|i| 0.5 * (f(v[i - 1]) + f(v[i])) * (t[i] - t[i - 1]))
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
    /// G's horizontal position, the time, the speed setpoint and G's
    /// forward speed of every row after settling.
    path: Vec<[f64; 2]>,
    times: Vec<f64>,
    setpoints: Vec<f64>,
    forward: Vec<f64>,
    /// Column of v_x in a row; None when the motion is imposed.
    forward_column: Option<usize>,
    last: Vec<f64>,
    max_roll: f64,
    max_pitch: f64,
    deep: Vec<bool>,
    /// Column of the first wheel centre in a row.
    wheel_column: usize,
    /// Axles (1-based wheels, rest x) whose sideways speed is measured.
    axles: Vec<(Vec<usize>, f64)>,
    /// Yaw of every row after settling.
    yaw: Vec<f64>,
    /// Per axle, its wheel centres' horizontal midpoint in every row after
    /// settling.
    axle_paths: Vec<Vec<[f64; 2]>>,
    /// On a soil, each wheel's slip and sinkage columns, and their sums,
    /// peaks and count after settling.
    soil: Vec<SoilTally>,
}

/// One wheel's slip and sinkage over the rows after settling.
#[derive(Clone, Copy, Debug, Default)]
struct SoilTally {
    slip_column: usize,
    sinkage_column: usize,
    rows: usize,
    slip_sum: f64,
    slip_peak: f64,
    sinkage_sum: f64,
    sinkage_peak: f64,
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
    /// The plant that ran, as the summary names it ([`plant_label`]).
    pub plant: String,
    /// Right-hand-side (or residual) evaluations.
    pub rhs_evals: u64,
    /// Accepted steps (or Newton iterations).
    pub steps: u64,
    /// Rejected steps.
    pub rejected_steps: u64,
    /// Jacobian evaluations.
    pub jacobian_evals: u64,
    /// LU factorizations.
    pub lu_decompositions: u64,
}

impl RunLog {
    /// A log for a run whose commands start at `settle`, of a rover with
    /// `dof` degrees of freedom and `wheels` wheels.
    pub fn new(settle: f64, dof: usize, wheels: usize) -> Self {
        Self {
            settle,
            deep: vec![false; wheels],
            // t, then x (dof columns), then w starting with v_x.
            forward_column: Some(1 + dof),
            wheel_column: 1 + 2 * dof,
            ..Self::default()
        }
    }

    /// Measure the sideways slides of these axles (each its wheels, 1-based,
    /// and its rest x; [`super::axles_by_rest_x`] groups them).
    pub fn with_axles(self, axles: Vec<(Vec<usize>, f64)>) -> Self {
        Self {
            axle_paths: vec![Vec::new(); axles.len()],
            axles,
            ..self
        }
    }

    /// Tally each wheel's slip and sinkage on a soil, from the columns
    /// named `slip{j}` and `sinkage{j}` of `header` (none on rigid ground).
    pub fn with_soil(mut self, header: &[String], wheels: usize) -> Self {
        let at = |name: String| header.iter().position(|h| *h == name);
        self.soil = (1..=wheels)
            .map_while(|j| {
                Some(SoilTally {
                    slip_column: at(format!("slip{j}"))?,
                    sinkage_column: at(format!("sinkage{j}"))?,
                    slip_peak: f64::NEG_INFINITY,
                    sinkage_peak: f64::NEG_INFINITY,
                    ..SoilTally::default()
                })
            })
            .collect();
        self
    }

    /// A log for a run that imposes the rover's motion (the quasi-static
    /// level): it cannot stall, and its rows carry no velocities.
    pub fn imposed(settle: f64, wheels: usize) -> Self {
        Self {
            forward_column: None,
            ..Self::new(settle, 0, wheels)
        }
    }

    /// Record a row ([`rover_runtime::row::Columns`]: the columns of the CSV, the speed setpoint
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
            for w in &mut self.soil {
                let (slip, sinkage) = (row[w.slip_column], row[w.sinkage_column]);
                w.rows += 1;
                w.slip_sum += slip;
                w.slip_peak = w.slip_peak.max(slip);
                w.sinkage_sum += sinkage;
                w.sinkage_peak = w.sinkage_peak.max(sinkage);
            }
            self.path.push([row[1], row[2]]);
            self.times.push(row[0]);
            self.setpoints.push(row.last().copied().unwrap_or(0.0));
            if let Some(k) = self.forward_column {
                self.forward.push(row.get(k).copied().unwrap_or(0.0));
            }
            self.yaw.push(row[6]);
            for ((wheels, _), path) in self.axles.iter().zip(&mut self.axle_paths) {
                let mut mid = [0.0; 2];
                for &j in wheels {
                    let c = self.wheel_column + 3 * (j - 1);
                    mid[0] += row[c] / wheels.len() as f64;
                    mid[1] += row[c + 1] / wheels.len() as f64;
                }
                path.push(mid);
            }
        }
    }

    /// G's horizontal position at each output instant after settling, with
    /// its time.
    pub fn track(&self) -> impl Iterator<Item = (f64, [f64; 2])> + '_ {
        self.times.iter().copied().zip(self.path.iter().copied())
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
            commanded_distance_m: integral(&self.times, &self.setpoints, f64::abs),
            stalled: self.forward_column.and_then(|_| {
                stall(
                    &Track {
                        times: &self.times,
                        path: &self.path,
                        setpoints: &self.setpoints,
                        forward: &self.forward,
                    },
                    header
                        .iter()
                        .zip(&self.last)
                        .filter(|(name, _)| name.starts_with("tau"))
                        .map(|(_, v)| *v)
                        .collect(),
                )
            }),
            runaway: self.forward_column.and_then(|_| {
                runaway(
                    &Track {
                        times: &self.times,
                        path: &self.path,
                        setpoints: &self.setpoints,
                        forward: &self.forward,
                    },
                    &self.yaw,
                    end.kinematic_radius,
                )
            }),
            ruts: None,
            rut_grid: None,
            soil: (!self.soil.is_empty()).then(|| {
                self.soil
                    .iter()
                    .enumerate()
                    .filter(|(_, w)| w.rows > 0)
                    .map(|(j, w)| WheelSoil {
                        wheel: j + 1,
                        mean_slip: w.slip_sum / w.rows as f64,
                        peak_slip: w.slip_peak,
                        mean_sinkage_m: w.sinkage_sum / w.rows as f64,
                        peak_sinkage_m: w.sinkage_peak,
                    })
                    .collect()
            }),
            slide: if self.axles.is_empty() {
                None
            } else {
                slide(
                    &SlideTrack {
                        times: &self.times,
                        yaw: &self.yaw,
                        path: &self.path,
                        axles: &self.axle_paths,
                    },
                    &self.axles,
                )
            },
            path_deviation: None,
            wall_time_s: end.wall_time_s,
            real_time_factor: if end.wall_time_s > 0.0 {
                end.t_end / end.wall_time_s
            } else {
                f64::INFINITY
            },
            integrator: end.integrator,
            plant: end.plant,
            rhs_evals: end.rhs_evals,
            steps: end.steps,
            rejected_steps: end.rejected_steps,
            jacobian_evals: end.jacobian_evals,
            lu_decompositions: end.lu_decompositions,
            profile: None,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Rows every 0.1 s over `seconds`: G at `x(t)` driving along X, with
    /// the forward speed x'(t), and the setpoint `v`.
    struct Rows {
        t: Vec<f64>,
        p: Vec<[f64; 2]>,
        v: Vec<f64>,
        fwd: Vec<f64>,
    }

    fn rows(seconds: f64, v: f64, x: impl Fn(f64) -> f64) -> Rows {
        let n = (seconds * 10.0).round() as usize;
        let t: Vec<f64> = (0..=n).map(|i| i as f64 * 0.1).collect();
        let h = 1e-6;
        Rows {
            p: t.iter().map(|&t| [x(t), 0.0]).collect(),
            fwd: t
                .iter()
                .map(|&t| (x(t + h) - x(t - h)) / (2.0 * h))
                .collect(),
            v: vec![v; n + 1],
            t,
        }
    }

    fn judge(r: &Rows) -> Option<Stall> {
        let track = Track {
            times: &r.t,
            path: &r.p,
            setpoints: &r.v,
            forward: &r.fwd,
        };
        stall(&track, vec![])
    }

    #[test]
    fn a_rover_following_its_command_has_not_stalled() {
        let r = rows(30.0, 0.2, |t| 0.2 * t);
        assert_eq!(judge(&r), None);
        assert!((integral(&r.t, &r.v, f64::abs) - 6.0).abs() < 1e-9);
        // Backwards as commanded.
        assert_eq!(judge(&rows(30.0, -0.2, |t| -0.2 * t)), None);
    }

    #[test]
    fn a_rover_stuck_at_the_end_has_stalled_over_the_last_window() {
        // Drives 20 s, then stops dead for the last 10 s.
        let s = judge(&rows(30.0, 0.2, |t| 0.2 * t.min(20.0))).expect("stalled");
        assert!((s.window_s - STALL_WINDOW).abs() < 1e-9);
        assert!((s.commanded_m - 2.0).abs() < 1e-9);
        // (The first interval of the window still holds the last 5 mm.)
        assert!(s.moved_m < 1e-12 && s.progress_m.abs() < 0.006, "{s:?}");
        // Still crawling at 9 % of the command: stalled; at 11 %: not.
        for (share, stalled) in [(0.09, true), (0.11, false)] {
            let r = rows(30.0, 0.2, |t| share * 0.2 * t);
            assert_eq!(judge(&r).is_some(), stalled, "{share}");
        }
    }

    #[test]
    fn a_rover_sliding_back_has_stalled_though_it_moved() {
        // Commanded forward, sliding back down a slope at 5 cm/s.
        let s = judge(&rows(30.0, 0.2, |t| -0.05 * t)).expect("stalled");
        assert!((s.moved_m - 0.5).abs() < 1e-9, "{s:?}");
        assert!((s.progress_m + 0.5).abs() < 1e-6, "{s:?}");
    }

    #[test]
    fn a_rover_without_speed_command_or_with_a_short_run_is_judged_fairly() {
        // Parked on purpose: nothing was asked, nothing is reported.
        assert_eq!(judge(&rows(30.0, 0.0, |_| 0.0)), None);
        // A run shorter than the window is judged over all of it.
        let s = judge(&rows(4.0, 0.2, |_| 0.0)).expect("stalled");
        assert!((s.window_s - 4.0).abs() < 1e-9 && (s.commanded_m - 0.8).abs() < 1e-9);
        // Too little asked to judge (under 1 cm).
        assert_eq!(judge(&rows(4.0, 0.002, |_| 0.0)), None);
        // No rows after settling.
        assert_eq!(judge(&rows(-1.0, 0.2, |_| 0.0)), None);
    }
}
