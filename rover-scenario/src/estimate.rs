//! A sensor log estimated (`rover estimate`): the scenario's rover as
//! the filter's process model — the same plant, ground and contact as the
//! run that made the log, on the map the estimator carries, with no
//! controller loops (the commands the rover's computer issued are the
//! filter's inputs) — the model-based filter and the dead-reckoning
//! baseline run over the log, and both measured against the truth when
//! it is known (docs/ESTIMATE.md).

use std::io::Write;
use std::path::Path;
use std::time::{Duration, Instant};

use rover_dynamics::Model;
use rover_dynamics::plant::Plant;
use rover_estimate::consistency::{NeesTally, Rms};
use rover_estimate::{
    DeadReckoning, DeadReckoningConfig, Estimator, FilterConfig, InitialSigma, SensorConfig,
    SensorSample,
};
use rover_integrate::OdeSystem;
use rover_runtime::control::wrap_angle;
use rover_runtime::sim::RoverSystem;
use rover_runtime::terrain::Terrain;
use serde::Serialize;

use crate::output::csv_writer::write_finite_row;
use crate::output::plant_label;
use crate::scenario::Scenario;
use crate::simulate::{SetupError, ground_of, initial_state, settle_into_soil};
use crate::truth_log::{TruthLog, state_columns};

/// The terrain map an estimator carries.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub enum EstimateMap {
    /// The scenario's own terrain: the truth's.
    #[default]
    True,
    /// The scenario's terrain with features shorter than `cutoff` \[m\]
    /// removed, as an orbital map would give it
    /// ([`Terrain::smoothed`]).
    Smoothed {
        /// The shortest wavelength kept \[m\].
        cutoff: f64,
    },
}

/// The rover of `scenario` as the filter's process model, on `map`, and
/// the run's initial state in the model's layout `[x; w; ω]` (computed on
/// the true terrain: the rover knows where it starts). The system is open
/// loop ([`RoverSystem::open_loop`]): the filter sets the torques and
/// steering it reads from the log.
pub fn process_system<P: Plant>(
    plant: P,
    model: &Model,
    scenario: &Scenario,
    base_dir: &Path,
    map: EstimateMap,
) -> Result<(RoverSystem<P, Terrain>, Vec<f64>), SetupError> {
    if scenario.free_flight {
        return Err(SetupError::Initial {
            field: "free_flight",
            message: "a rover in free flight has no ground for the estimator's model; estimate a run on a terrain".into(),
        });
    }
    let truth = scenario.terrain.build(base_dir)?;
    let mut y = initial_state(model, scenario, Some(&truth))?;
    let carried = match map {
        EstimateMap::True => truth,
        EstimateMap::Smoothed { cutoff } => truth.smoothed(cutoff)?,
    };
    let ground = ground_of(scenario, carried, model, base_dir)?;
    settle_into_soil(&ground, model, scenario, &mut y);
    let mut sys = RoverSystem::open_loop(plant, Some(ground), model)?;
    // The scenario's state carries the speed loop's integral after [x; w]:
    // the open loop has none.
    y.truncate(2 * model.dof());
    y.resize(sys.dim(), 0.0);
    sys.roll_spins(0.0, &mut y);
    Ok((sys, y))
}

/// What `rover estimate` runs besides the log: the map, the filter's
/// tuning and start, and the baseline's gains.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct EstimateOptions {
    /// The map the filter carries.
    pub map: EstimateMap,
    /// The filter's tuning and initial standard deviations: a file's
    /// values over the preset the run calls for ([`Preset::of`]).
    pub tuning: Tuning,
    /// The dead-reckoning baseline's gains.
    pub dead_reckoning: DeadReckoningConfig,
}

/// A state estimate's errors against the truth, at the truth's instants.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct Accuracy {
    /// RMS roll error [°].
    pub roll_deg: f64,
    /// RMS pitch error [°].
    pub pitch_deg: f64,
    /// RMS yaw error [°].
    pub yaw_deg: f64,
    /// Each suspension coordinate's RMS error (rad, or m).
    pub suspension: Vec<f64>,
    /// The largest RMS error of an angular suspension coordinate [°].
    pub suspension_deg_max: Option<f64>,
    /// RMS of |v − v_true|, G's velocity in body components [m/s].
    pub velocity: f64,
    /// RMS of |Ω − Ω_true| [rad/s].
    pub angular_velocity: f64,
    /// G's horizontal position error at the end \[m\].
    pub final_drift: f64,
    /// The same over the distance travelled (the truth's horizontal path).
    pub drift_fraction: f64,
    /// The largest horizontal position error over the run \[m\].
    pub max_drift: f64,
    /// On a soil, the largest of the wheels' RMS slip errors.
    pub slip_max: Option<f64>,
}

/// The filter's consistency over the run (docs/ESTIMATE.md, "Consistency").
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct Consistency {
    /// Degrees of freedom of the NEES, 2N.
    pub dof: usize,
    /// The 95 % interval of χ²(2N).
    pub bounds: [f64; 2],
    /// Truth instants compared.
    pub samples: usize,
    /// The fraction of them whose NEES is inside the interval.
    pub fraction_inside: f64,
    /// How many fell below it (a timid filter) and above it (an
    /// overconfident one).
    pub below: usize,
    /// See `below`.
    pub above: usize,
    /// The mean NEES (2N when consistent).
    pub mean: f64,
}

/// What an estimation run did: how it ended, its accuracy against the
/// truth when known, its consistency and its cost.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct EstimateSummary {
    /// `completed`, or `failed` with `error`: the rows before the failure
    /// are written and kept.
    pub status: String,
    /// Why it failed, with the time.
    pub error: Option<String>,
    /// The last sample's time estimated \[s\].
    pub t_end: f64,
    /// Samples taken.
    pub samples: usize,
    /// The map the filter carried.
    pub map: String,
    /// The tuning's preset (`Preset`), under the tuning file's fields.
    pub preset: String,
    /// The process model's plant.
    pub plant: String,
    /// The truth's horizontal path length \[m\].
    pub distance: Option<f64>,
    /// The model-based filter's errors.
    pub filter: Option<Accuracy>,
    /// Dead reckoning's errors on the same log.
    pub dead_reckoning: Option<Accuracy>,
    /// Dead reckoning's final drift over the filter's.
    pub drift_ratio: Option<f64>,
    /// The filter's consistency.
    pub consistency: Option<Consistency>,
    /// Wall time of the estimation \[s\].
    pub wall_time: f64,
    /// Mean wall time of one filter step (a prediction and the updates of
    /// one sample) \[µs\].
    pub step_us: f64,
}

/// Running errors of one estimator against the truth.
#[derive(Clone, Debug)]
struct AccuracyTally {
    n: usize,
    angles: [Rms; 3],
    suspension: Vec<Rms>,
    velocity: Rms,
    angular_velocity: Rms,
    slip: Vec<Rms>,
    final_drift: f64,
    max_drift: f64,
}

impl AccuracyTally {
    fn new(n: usize, wheels: usize) -> Self {
        Self {
            n,
            angles: [Rms::default(); 3],
            suspension: vec![Rms::default(); n - 6],
            velocity: Rms::default(),
            angular_velocity: Rms::default(),
            slip: vec![Rms::default(); wheels],
            final_drift: 0.0,
            max_drift: 0.0,
        }
    }

    /// One truth instant: the estimate `y` and the truth `truth` (both
    /// `[x; w]` first), the slips when on a soil.
    fn add(&mut self, y: &[f64], truth: &[f64], slips: Option<(&[f64], &[f64])>) {
        let n = self.n;
        let drift = (y[0] - truth[0]).hypot(y[1] - truth[1]);
        self.final_drift = drift;
        self.max_drift = self.max_drift.max(drift);
        for k in 0..3 {
            self.angles[k].add(wrap_angle(y[3 + k] - truth[3 + k]));
        }
        for (i, r) in self.suspension.iter_mut().enumerate() {
            r.add(y[6 + i] - truth[6 + i]);
        }
        let norm = |a: &[f64], b: &[f64]| {
            a.iter()
                .zip(b)
                .map(|(p, q)| (p - q) * (p - q))
                .sum::<f64>()
                .sqrt()
        };
        self.velocity.add(norm(&y[n..n + 3], &truth[n..n + 3]));
        self.angular_velocity
            .add(norm(&y[n + 3..n + 6], &truth[n + 3..n + 6]));
        if let Some((est, tru)) = slips {
            for ((r, e), t) in self.slip.iter_mut().zip(est).zip(tru) {
                r.add(e - t);
            }
        }
    }

    fn finish(&self, distance: f64, linear: &[bool]) -> Accuracy {
        let angular = self
            .suspension
            .iter()
            .zip(linear)
            .filter(|(_, l)| !**l)
            .map(|(r, _)| r.value().to_degrees());
        let slip_counted = self.slip.iter().any(|r| r.count() > 0);
        Accuracy {
            roll_deg: self.angles[0].value().to_degrees(),
            pitch_deg: self.angles[1].value().to_degrees(),
            yaw_deg: self.angles[2].value().to_degrees(),
            suspension: self.suspension.iter().map(Rms::value).collect(),
            suspension_deg_max: angular.reduce(f64::max),
            velocity: self.velocity.value(),
            angular_velocity: self.angular_velocity.value(),
            final_drift: self.final_drift,
            drift_fraction: if distance > 0.0 {
                self.final_drift / distance
            } else {
                0.0
            },
            max_drift: self.max_drift,
            slip_max: slip_counted.then(|| self.slip.iter().map(Rms::value).fold(0.0, f64::max)),
        }
    }
}

/// The truth's horizontal path length up to each of its rows.
fn path_lengths(truth: &TruthLog) -> Vec<f64> {
    let mut total = 0.0;
    let mut out = Vec::with_capacity(truth.t.len());
    for (k, y) in truth.y.iter().enumerate() {
        if k > 0 {
            let p = &truth.y[k - 1];
            total += (y[0] - p[0]).hypot(y[1] - p[1]);
        }
        out.push(total);
    }
    out
}

/// Why an estimation could not start, or could not write.
#[derive(Debug, thiserror::Error)]
pub enum EstimateRunError {
    /// The scenario's rover and ground could not be set up.
    #[error(transparent)]
    Setup(#[from] SetupError),
    /// The filter or the baseline refused its start (a setting, the first sample).
    #[error("the estimator cannot start: {0}")]
    Start(String),
    /// The log holds no sample.
    #[error("the sensor log holds no sample")]
    Empty,
    /// An output could not be written.
    #[error("writing {file}: {source}")]
    Output {
        /// The output.
        file: &'static str,
        /// Why.
        source: std::io::Error,
    },
}

/// The columns of `estimate.csv` for a rover of `m` suspension
/// coordinates and `wheels` wheels: t, the state (with each wheel's spin
/// `omega{j}` on a soil), each state entry's 1σ (`sigma_<name>`), the
/// wheels' normal loads and slips, then with an IMU its biases and their
/// 1σ.
pub fn estimate_columns(m: usize, wheels: usize, soil: bool, imu: bool) -> Vec<String> {
    let mut state = state_columns(m);
    if soil {
        state.extend((1..=wheels).map(|j| format!("omega{j}")));
    }
    let mut names = vec!["t".to_string()];
    names.extend(state.iter().cloned());
    names.extend(state.iter().map(|s| format!("sigma_{s}")));
    names.extend((1..=wheels).map(|j| format!("Fn{j}")));
    names.extend((1..=wheels).map(|j| format!("slip{j}")));
    if imu {
        let biases = ["bgx", "bgy", "bgz", "bax", "bay", "baz"];
        names.extend(biases.iter().map(|s| s.to_string()));
        names.extend(biases.iter().map(|s| format!("sigma_{s}")));
    }
    names
}

/// The columns of `dead_reckoning.csv`: t and the state `[x; w]`.
pub fn baseline_columns(m: usize) -> Vec<String> {
    let mut names = vec!["t".to_string()];
    names.extend(state_columns(m));
    names
}

/// Runs the model-based filter and the dead-reckoning baseline over the
/// sensor log `samples` of a run of `scenario` (its rover `plant`,
/// `model`, its linear coordinates `linear`), writing one row per sample
/// to `estimate_csv` and `baseline_csv`, and measuring both against
/// `truth` when given.
///
/// The first sample (t = 0) starts both at the scenario's initial state;
/// each later one is predicted to with the commands of the one before
/// (held over the interval, as the rover's computer held them) and then
/// taken. A filter or baseline that fails at a sample ends the run there:
/// the summary says `failed` with the time and why, and the rows written
/// before are kept.
#[allow(clippy::too_many_arguments)]
pub fn estimate_log<P: Plant, W: Write, V: Write>(
    plant: P,
    model: &Model,
    linear: &[bool],
    scenario: &Scenario,
    base_dir: &Path,
    sensors: &SensorConfig,
    samples: &[SensorSample],
    truth: Option<&TruthLog>,
    options: &EstimateOptions,
    estimate_csv: W,
    baseline_csv: V,
) -> Result<EstimateSummary, EstimateRunError> {
    let plant_name = plant_label(&plant);
    let (n, m, wheels) = (model.dof(), model.m(), model.wheels.len());
    let (sys, y0) = process_system(plant, model, scenario, base_dir, options.map)?;
    let first = samples.first().ok_or(EstimateRunError::Empty)?;
    let soil = !sys.spin_range().is_empty();
    let preset = Preset::of(options.map, soil);
    let (config, initial) = options.tuning.resolve(preset);
    let mut filter = Estimator::new(sys, sensors, config, first.t, &y0, &initial)
        .map_err(|e| EstimateRunError::Start(e.to_string()))?;
    let radii: Vec<f64> = model.wheels.iter().map(|w| w.radius).collect();
    let mut baseline = DeadReckoning::new(
        options.dead_reckoning,
        sensors,
        &radii,
        model.gravity,
        first.t,
        &y0[..n],
    )
    .map_err(|e| EstimateRunError::Start(e.to_string()))?;
    let imu = sensors.imu.is_some();
    let est_names = estimate_columns(m, wheels, soil, imu);
    let mut est_out = RowWriter::new(estimate_csv, &est_names).map_err(output("estimate.csv"))?;
    let mut dr_out =
        RowWriter::new(baseline_csv, &baseline_columns(m)).map_err(output("dead_reckoning.csv"))?;

    let paths = truth.map(path_lengths);
    let mut tallies = truth.map(|_| (AccuracyTally::new(n, wheels), AccuracyTally::new(n, wheels)));
    let mut nees = NeesTally::new(2 * n);
    let mut next_truth = 0;
    let mut row = vec![0.0; est_names.len()];
    // dead_reckoning.csv's row: t, then the baseline's [x; w].
    let mut dr_row = vec![0.0; 1 + 2 * n];
    let (mut normal, mut slip) = (vec![0.0; wheels], vec![0.0; wheels]);
    let mut truth_state = vec![0.0; y0.len()];
    let mut summary = EstimateSummary {
        status: "completed".into(),
        map: map_label(options.map),
        preset: preset.name().into(),
        plant: plant_name,
        ..EstimateSummary::default()
    };
    let started = Instant::now();
    let mut filter_time = Duration::ZERO;
    for (k, s) in samples.iter().enumerate() {
        let step_start = Instant::now();
        let stepped = if k == 0 {
            filter.update(s).map_err(|e| e.to_string())
        } else {
            let prev = &samples[k - 1];
            filter
                .predict(s.t - prev.t, &prev.torques, &prev.steering)
                .and_then(|()| filter.update(s))
                .map_err(|e| e.to_string())
        };
        filter_time += step_start.elapsed();
        let stepped = stepped.and_then(|()| {
            if k == 0 {
                Ok(())
            } else {
                baseline
                    .update(s)
                    .map_err(|e| format!("dead reckoning: {e}"))
            }
        });
        let outputs = stepped.and_then(|()| {
            filter
                .wheel_outputs(&mut normal, &mut slip)
                .map_err(|e| e.to_string())
        });
        if let Err(why) = outputs {
            summary.status = "failed".into();
            summary.error = Some(format!("at t = {} s: {why}", s.t));
            break;
        }
        fill_estimate_row(&filter, s.t, &normal, &slip, &mut row);
        est_out.write(&row).map_err(output("estimate.csv"))?;
        dr_row[0] = s.t;
        let (x_dr, w_dr) = dr_row[1..].split_at_mut(n);
        baseline.state(x_dr, w_dr);
        dr_out
            .write(&dr_row)
            .map_err(output("dead_reckoning.csv"))?;
        summary.samples = k + 1;
        summary.t_end = s.t;
        let Some(truth) = truth else { continue };
        while next_truth < truth.t.len() && truth.t[next_truth] < s.t - 1e-9 * (1.0 + s.t) {
            next_truth += 1;
        }
        if next_truth >= truth.t.len() || (truth.t[next_truth] - s.t).abs() > 1e-9 * (1.0 + s.t) {
            continue;
        }
        let tru = &truth.y[next_truth];
        let slips = truth.slip.as_ref().map(|rows| rows[next_truth].as_slice());
        let Some((tally, dr_tally)) = tallies.as_mut() else {
            continue;
        };
        tally.add(filter.state(), tru, slips.map(|t| (slip.as_slice(), t)));
        dr_tally.add(&dr_row[1..], tru, None);
        truth_state[..2 * n].copy_from_slice(tru);
        truth_state[2 * n..].copy_from_slice(&filter.state()[2 * n..]);
        match filter.nees(&truth_state) {
            Ok(v) => nees.add(v),
            Err(e) => {
                summary.status = "failed".into();
                summary.error = Some(format!("at t = {} s: {e}", s.t));
                break;
            }
        }
        next_truth += 1;
    }
    est_out.finish().map_err(output("estimate.csv"))?;
    dr_out.finish().map_err(output("dead_reckoning.csv"))?;
    summary.wall_time = started.elapsed().as_secs_f64();
    summary.step_us = 1e6 * filter_time.as_secs_f64() / summary.samples.max(1) as f64;
    if let (Some((tally, dr_tally)), Some(paths), Some(truth)) = (&tallies, &paths, truth) {
        // The distance up to the last instant estimated.
        let end = summary.t_end + 1e-9 * (1.0 + summary.t_end);
        let reached = truth.t.partition_point(|t| *t <= end);
        let upto = reached.checked_sub(1).map_or(0.0, |k| paths[k]);
        summary.distance = Some(upto);
        let filter_acc = tally.finish(upto, linear);
        let dr_acc = dr_tally.finish(upto, linear);
        summary.drift_ratio =
            (filter_acc.final_drift > 0.0).then(|| dr_acc.final_drift / filter_acc.final_drift);
        summary.filter = Some(filter_acc);
        summary.dead_reckoning = Some(dr_acc);
        let (lo, hi) = nees.bounds();
        let (below, above) = nees.outside();
        summary.consistency = Some(Consistency {
            dof: 2 * n,
            bounds: [lo, hi],
            samples: nees.count(),
            fraction_inside: nees.fraction_inside(),
            below,
            above,
            mean: nees.mean(),
        });
    }
    Ok(summary)
}

/// The map's name in the summary.
fn map_label(map: EstimateMap) -> String {
    match map {
        EstimateMap::True => "true".into(),
        EstimateMap::Smoothed { cutoff } => format!("smoothed below {cutoff} m"),
    }
}

/// An output's write error, named.
fn output(file: &'static str) -> impl Fn(std::io::Error) -> EstimateRunError {
    move |source| EstimateRunError::Output { file, source }
}

/// The row of `estimate.csv` at the filter's estimate (see
/// [`estimate_columns`]): t, the state, its 1σ, the wheels' loads and
/// slips, the biases and their 1σ.
fn fill_estimate_row<M: rover_estimate::ProcessModel>(
    filter: &Estimator<M>,
    t: f64,
    normal: &[f64],
    slip: &[f64],
    row: &mut [f64],
) {
    let y = filter.state();
    let dim = y.len();
    row[0] = t;
    row[1..=dim].copy_from_slice(y);
    // The lengths are the filter's own: it cannot refuse them.
    let _ = filter.state_sigma(&mut row[1 + dim..1 + 2 * dim]);
    let mut at = 1 + 2 * dim;
    for v in normal.iter().chain(slip) {
        row[at] = *v;
        at += 1;
    }
    if let Some((gyro, accel)) = filter.biases() {
        row[at..at + 3].copy_from_slice(&gyro);
        row[at + 3..at + 6].copy_from_slice(&accel);
        let len = filter.error_dim();
        let p = filter.covariance();
        for k in 0..6 {
            let i = len - 6 + k;
            row[at + 6 + k] = p[i * len + i].max(0.0).sqrt();
        }
    }
}

/// Rows of numbers under a header, a non-finite value refused (a NaN
/// never reaches the file as if it were a result).
struct RowWriter<W: Write> {
    out: W,
    names: Vec<String>,
}

impl<W: Write> RowWriter<W> {
    fn new(mut out: W, names: &[String]) -> std::io::Result<Self> {
        writeln!(out, "{}", names.join(","))?;
        Ok(Self {
            out,
            names: names.to_vec(),
        })
    }

    fn write(&mut self, row: &[f64]) -> std::io::Result<()> {
        write_finite_row(&mut self.out, &self.names, row)
    }

    fn finish(mut self) -> std::io::Result<()> {
        self.out.flush()
    }
}

impl crate::prepare::Prepared {
    /// The scenario's `[sensors]`, which says what its sensor log holds;
    /// a scenario without is an error located at the scenario.
    pub fn sensor_config(&self) -> Result<&SensorConfig, crate::prepare::PrepareError> {
        self.scenario.sensors.as_ref().ok_or_else(|| {
            self.locate(SetupError::Unsupported {
                field: "sensors",
                message: "the scenario declares no [sensors], which say what its sensor log holds\n  = help: give the scenario whose run wrote the log".into(),
            })
        })
    }

    /// Estimates the sensor log `samples` of this scenario's run (see
    /// [`estimate_log`]) with its rover's plant (`generic`: the generic
    /// plant even for a built-in rover), a setup error located at the
    /// scenario's offending field.
    pub fn estimate<W: Write, V: Write>(
        &self,
        generic: bool,
        samples: &[SensorSample],
        truth: Option<&TruthLog>,
        options: &EstimateOptions,
        estimate_csv: W,
        baseline_csv: V,
    ) -> Result<EstimateSummary, crate::prepare::PrepareError> {
        let sensors = self.sensor_config()?;
        let (model, linear) = (&self.spec.model, &self.spec.coordinate_linear);
        let (scenario, base) = (&self.scenario, &self.base);
        let run = match self.plant(generic)? {
            crate::prepare::RunPlant::Generated(p) => estimate_log(
                p,
                model,
                linear,
                scenario,
                base,
                sensors,
                samples,
                truth,
                options,
                estimate_csv,
                baseline_csv,
            ),
            crate::prepare::RunPlant::Generic(p) => estimate_log(
                p,
                model,
                linear,
                scenario,
                base,
                sensors,
                samples,
                truth,
                options,
                estimate_csv,
                baseline_csv,
            ),
        };
        run.map_err(|e| match e {
            EstimateRunError::Setup(s) => self.locate(s),
            other => crate::prepare::PrepareError::Estimate(other.to_string()),
        })
    }
}

/// Which tuning a run starts from: the model is the rover's own (its
/// true map, rigid ground), or only approximates its world (a smoothed
/// map, a soil law). docs/ESTIMATE.md, "Tuning".
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Preset {
    /// [`FilterConfig::default`] and [`InitialSigma::default`].
    ExactModel,
    /// [`FilterConfig::approximate_model`] and
    /// [`InitialSigma::approximate_model`].
    ApproximateModel,
}

impl Preset {
    /// The preset of a run on `map`, on a soil when `soil`.
    pub fn of(map: EstimateMap, soil: bool) -> Self {
        if soil || map != EstimateMap::True {
            Preset::ApproximateModel
        } else {
            Preset::ExactModel
        }
    }

    /// Its name in the summary.
    pub fn name(self) -> &'static str {
        match self {
            Preset::ExactModel => "exact model",
            Preset::ApproximateModel => "approximate model",
        }
    }

    /// Its tuning and initial standard deviations.
    pub fn values(self) -> (FilterConfig, InitialSigma) {
        match self {
            Preset::ExactModel => (FilterConfig::default(), InitialSigma::default()),
            Preset::ApproximateModel => (
                FilterConfig::approximate_model(),
                InitialSigma::approximate_model(),
            ),
        }
    }
}

/// A filter's tuning as a file gives it (`rover estimate --tuning`): the
/// `[filter]` table ([`FilterConfig`]'s fields) and the `[initial]` table
/// ([`InitialSigma`]'s), each field optional: a field the file leaves
/// out keeps the run's preset value ([`Preset`]).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Tuning {
    /// The file's tables, checked against the fields when read.
    overrides: toml::Table,
}

/// The shape a tuning file is checked against.
#[derive(serde::Deserialize)]
#[serde(deny_unknown_fields)]
#[allow(dead_code)] // read for its checks only
struct TuningFile {
    #[serde(default)]
    filter: FilterConfig,
    #[serde(default)]
    initial: InitialSigma,
}

impl Tuning {
    /// The preset's values with this tuning's fields over them.
    pub fn resolve(&self, preset: Preset) -> (FilterConfig, InitialSigma) {
        let (filter, initial) = preset.values();
        (
            overlay(filter, self.overrides.get("filter")),
            overlay(initial, self.overrides.get("initial")),
        )
    }
}

/// `base` with the fields of `table` (checked when the file was read)
/// over it.
fn overlay<T>(base: T, table: Option<&toml::Value>) -> T
where
    T: serde::Serialize + serde::de::DeserializeOwned + Clone,
{
    let Some(toml::Value::Table(fields)) = table else {
        return base;
    };
    let Ok(toml::Value::Table(mut merged)) = toml::Value::try_from(base.clone()) else {
        return base;
    };
    for (k, v) in fields {
        merged.insert(k.clone(), v.clone());
    }
    toml::Value::Table(merged).try_into().unwrap_or(base)
}

/// Reads a [`Tuning`] file; the error names the file, the line and the
/// field.
pub fn read_tuning(path: &Path) -> Result<Tuning, String> {
    let text = rover_files::read_text(path, rover_files::Limit::Text)
        .map_err(|e| format!("{}: cannot read it: {e}", path.display()))?;
    let located = |e: toml::de::Error| {
        let line = e
            .span()
            .map(|s| format!(":{}", 1 + text[..s.start].matches('\n').count()))
            .unwrap_or_default();
        format!(
            "{}{line}: {}\n  = help: the tuning file has a [filter] table (substeps, jacobian_every, position_noise, attitude_noise, suspension_noise, velocity_noise, angular_velocity_noise, suspension_rate_noise, spin_noise, wheel_rate_sigma, accel_model_sigma, torque_sigma, torque_response_every, torque_change_scale) and an [initial] table (position, attitude, suspension, velocity, angular_velocity, suspension_rate, spin); docs/ESTIMATE.md explains each",
            path.display(),
            e.message()
        )
    };
    toml::from_str::<TuningFile>(&text).map_err(located)?;
    let overrides = toml::from_str::<toml::Table>(&text).map_err(located)?;
    Ok(Tuning { overrides })
}
