//! A whole run from a scenario: build the pieces, place the rover, run,
//! write the CSV, summarize (the CLI adds plots and the progress bar;
//! [`crate::Simulation`] assembles the same run in Rust).

use std::io::Write;
use std::path::Path;
use std::sync::atomic::AtomicBool;
use std::time::Instant;

use rover_dynamics::Model;
use rover_dynamics::attitude::Attitude;
use rover_dynamics::plant::Plant;

use crate::output::{
    CsvWriter, RowSink, RunEnd, RunLog, Status, Summary, axles_by_rest_x, plant_label,
};
use crate::scenario::{FidelityLevel, Scenario};
use crate::sensor_log::SensorLogWriter;
use rover_dynamics::wheel_ground::ContactMethod;
use rover_estimate::sensors::{SensorConfig, SensorSample};
use rover_estimate::{SensorSimulator, Truth};
use rover_integrate::{Integrator, OdeSystem};
use rover_runtime::control::Controller;
use rover_runtime::ground::Ground;
use rover_runtime::row::{Columns, RowInputs};
use rover_runtime::sim::{RoverSystem, RunError, RunOptions, Stop, run_with_sensors};
use rover_terrain::Terrain;

/// A run that could not start: the scenario does not fit the rover, or a
/// piece could not be built.
#[derive(Debug, thiserror::Error)]
pub enum SetupError {
    /// The terrain could not be built or loaded.
    #[error("{0}")]
    Terrain(#[from] rover_terrain::TerrainError),
    /// The controller does not fit the rover.
    #[error("{0}")]
    Control(#[from] rover_runtime::control::ControlError),
    /// The integrator's parameters are invalid.
    #[error("{0}")]
    Integrator(#[from] rover_integrate::ConfigError),
    /// The initial state does not fit the rover.
    #[error("initial.{field}: {message}")]
    Initial {
        /// The field.
        field: &'static str,
        /// What is wrong and how to fix it.
        message: String,
    },
    /// The soil cannot be read or is outside physics.
    #[error("terrain.{0}")]
    Soil(#[from] rover_runtime::soil::SoilError),
    /// A soil map or patch that cannot be built (boxed: it is the
    /// largest of these).
    #[error("{0}")]
    SoilMap(Box<crate::ground::SoilMapError>),
    /// A wheel the soil law cannot take.
    #[error("{0}\n  = help: give the rover description's wheels (or its [wheel_defaults]) `{field}`: {help}", field = .0.field(), help = soil_wheel_help(.0))]
    SoilWheel(#[from] rover_runtime::ground::SoilWheelError),
    /// Two settings of the scenario that do not go together.
    #[error("{field}: {message}")]
    Unsupported {
        /// The field.
        field: &'static str,
        /// What is wrong and how to fix it.
        message: String,
    },
    /// The rover starts off the terrain map.
    #[error("the rover starts off the terrain: {0}")]
    OffMap(rover_dynamics::height_field::OffMap),
    /// The CSV could not be started.
    #[error("cannot write the CSV: {0}")]
    Io(#[from] std::io::Error),
    /// Another sink of the rows (the MCAP log) could not be started or
    /// finished; the message names its file.
    #[error("{0}")]
    Sink(String),
    /// A quasi-static run has no path to follow.
    #[error("path_from: {0}")]
    Path(String),
    /// The plant and the model are of different rovers.
    #[error("{0}")]
    Mismatch(#[from] rover_runtime::described::Mismatch),
    /// The rover is larger than the generic plant supports.
    #[error("{0}")]
    TooLarge(#[from] rover_runtime::generic_plant::TooLarge),
    /// The quasi-static level found no equilibrium to start from.
    #[error("{0}")]
    QuasiStatic(#[from] rover_runtime::quasi_static::QuasiStaticError),
}

impl From<crate::ground::SoilMapError> for SetupError {
    fn from(e: crate::ground::SoilMapError) -> Self {
        SetupError::SoilMap(Box::new(e))
    }
}

impl SetupError {
    /// The scenario field the error is about, as a dotted path, when it has one.
    pub fn field_path(&self) -> Option<String> {
        match self {
            SetupError::Terrain(rover_terrain::TerrainError::Parameter { name, .. }) => {
                Some(format!("terrain.{name}"))
            }
            SetupError::Soil(_) => Some("terrain.soil".into()),
            SetupError::SoilMap(e) => Some(e.field_path()),
            SetupError::Control(e) => Some(format!("control.{}", e.field)),
            SetupError::Integrator(e) => Some(format!("integrator.{}.{}", e.method, e.field)),
            SetupError::Initial { field, .. } => Some(format!("initial.{field}")),
            SetupError::Unsupported { field, .. } => Some((*field).into()),
            _ => None,
        }
    }
}

fn sink_error(e: std::io::Error) -> SetupError {
    SetupError::Sink(e.to_string())
}

fn soil_wheel_help(e: &rover_runtime::ground::SoilWheelError) -> &'static str {
    match e {
        rover_runtime::ground::SoilWheelError::NoWidth { .. } => {
            "the tyre's width in metres, e.g. width = 0.16"
        }
        rover_runtime::ground::SoilWheelError::NoSpinInertia { .. } => {
            "the wheel's moment of inertia about its axle in kg·m² (with its drive train), or a wheel mass"
        }
    }
}

/// The initial state y = [x; w; ζ] of a scenario for a model, on `terrain`
/// (None: free flight).
pub fn initial_state(
    model: &Model,
    scenario: &Scenario,
    terrain: Option<&Terrain>,
) -> Result<Vec<f64>, SetupError> {
    let n = model.dof();
    let m = model.m();
    let init = &scenario.initial;
    let mut y = vec![0.0; 2 * n + 1];
    y[0] = init.xy[0];
    y[1] = init.xy[1];
    for k in 0..3 {
        y[3 + k] = init.attitude_deg[k].to_radians();
    }
    let susp = init.suspension.clone().unwrap_or_else(|| model.rest());
    if susp.len() != m {
        return Err(SetupError::Initial {
            field: "suspension",
            message: format!(
                "the rover has {m} suspension coordinates, the scenario gives {}",
                susp.len()
            ),
        });
    }
    for (i, (v, c)) in susp.iter().zip(&model.coordinates).enumerate() {
        if !v.is_finite() || *v < c.min || *v > c.max {
            return Err(SetupError::Initial {
                field: "suspension",
                message: format!(
                    "y{} = {v} lies outside its travel [{}, {}]",
                    i + 1,
                    c.min,
                    c.max
                ),
            });
        }
    }
    y[6..n].copy_from_slice(&susp);
    y[n..n + 3].copy_from_slice(&init.velocity);
    y[n + 3..n + 6].copy_from_slice(&init.angular_velocity);
    if let Some(r) = &init.suspension_rates {
        if r.len() != m {
            return Err(SetupError::Initial {
                field: "suspension_rates",
                message: format!(
                    "the rover has {m} suspension coordinates, the scenario gives {}",
                    r.len()
                ),
            });
        }
        y[n + 6..2 * n].copy_from_slice(r);
    }
    y[2] = match (init.z, terrain) {
        (Some(z), None) => z,
        (Some(z), Some(t)) => {
            // A wheel deeper than half its radius is not a start on the
            // ground but inside it: the tyre law does not hold there.
            let touching = wheel_touching_heights(model, &y[..n], t)?;
            for (j, (zj, w)) in touching.iter().zip(&model.wheels).enumerate() {
                if zj - z > 0.5 * w.radius {
                    let lowest = touching.iter().copied().fold(f64::NEG_INFINITY, f64::max);
                    return Err(SetupError::Initial {
                        field: "z",
                        message: format!(
                            "z = {z} m puts wheel {} {:.3} m into the ground, more than half its radius ({} m); give z ≥ {lowest:.4} m (every wheel at or above the ground), or leave z out to start with the lowest wheel touching",
                            j + 1,
                            zj - z,
                            w.radius
                        ),
                    });
                }
            }
            // A start so high that the rover falls for the whole run is no
            // drive (it would be reported as a stall, not as the mistake).
            let lowest = touching.iter().copied().fold(f64::NEG_INFINITY, f64::max);
            let drop = z - lowest;
            let fall = (2.0 * drop / model.gravity).sqrt();
            if drop > 0.0 && model.gravity > 0.0 && fall >= scenario.duration {
                return Err(SetupError::Initial {
                    field: "z",
                    message: format!(
                        "z = {z} m starts the lowest wheel {drop:.4e} m above the ground: it would fall for {fall:.3e} s, the whole run (duration = {} s); give z ≤ {lowest:.4} m plus the drop you mean, or leave z out to start with the lowest wheel touching",
                        scenario.duration
                    ),
                });
            }
            z
        }
        (None, None) => 0.0,
        (None, Some(t)) => wheel_touching_heights(model, &y[..n], t)?
            .into_iter()
            .fold(f64::NEG_INFINITY, f64::max),
    };
    Ok(y)
}

/// For each wheel, the Z of G at which it just touches the ground below
/// it; the largest is where the lowest wheel touches.
fn wheel_touching_heights(
    model: &Model,
    x: &[f64],
    terrain: &Terrain,
) -> Result<Vec<f64>, SetupError> {
    let attitude = Attitude::new(x[3], x[4], x[5]);
    rover_runtime::ground::touchdown_heights(model, [x[0], x[1]], attitude, &x[6..], terrain)
        .map_err(|e| SetupError::OffMap(e.off))
}

/// The ground of `scenario` on `terrain` for `model`: its contact search
/// and wheel law, and its soil if `[terrain]` has one (files relative to
/// `base_dir`).
pub fn ground_of(
    scenario: &Scenario,
    terrain: Terrain,
    model: &Model,
    base_dir: &Path,
) -> Result<Ground<Terrain>, SetupError> {
    let layout = scenario.terrain.soil_layout(base_dir, &terrain)?;
    let ground = scenario.contact.ground(terrain, model);
    let ground = match layout {
        Some(layout) => {
            let soils: Vec<_> = layout.soils.iter().map(|(_, s)| *s).collect();
            ground.with_soils(&soils, layout.map, model)?
        }
        None => ground,
    };
    Ok(match scenario.terrain.rut_cell()? {
        Some(cell) => ground.with_ruts(cell),
        None => ground,
    })
}

/// On a soil, a start whose height the scenario leaves to the ground
/// (no `initial.z`) is lowered by the wheels' mean sinkage at rest under
/// their static loads on flat ground: the rover starts sunk into the soil
/// instead of dropping into it (a landing whose impact the soil's damper
/// takes in a few milliseconds). Nothing on rigid ground.
pub fn settle_into_soil(
    ground: &Ground<Terrain>,
    model: &Model,
    scenario: &Scenario,
    y: &mut [f64],
) {
    if ground.soil().is_none() || scenario.initial.z.is_some() {
        return;
    }
    let Ok(loads) = rover_runtime::quasi_static::flat_ground_loads(model) else {
        return;
    };
    let sinkages = ground.rest_sinkages(&loads);
    if !sinkages.is_empty() {
        y[2] -= sinkages.iter().sum::<f64>() / sinkages.len() as f64;
    }
}

/// The rover of `scenario` as an ODE system — its terrain (none in free
/// flight), ground, controller and `plant` — and its initial state, the
/// integral states beyond the speed loop's at 0: what a whole run and a
/// stepped one start from.
pub(crate) fn system_of<P: Plant>(
    plant: P,
    model: &Model,
    scenario: &Scenario,
    base_dir: &Path,
) -> Result<(RoverSystem<P, Terrain>, Vec<f64>), SetupError> {
    let terrain = if scenario.free_flight {
        None
    } else {
        Some(scenario.terrain.build(base_dir)?)
    };
    let mut y = initial_state(model, scenario, terrain.as_ref())?;
    let ground = match terrain {
        None => None,
        Some(t) => Some(ground_of(scenario, t, model, base_dir)?),
    };
    if let Some(g) = &ground {
        settle_into_soil(g, model, scenario, &mut y);
    }
    let control = Controller::new_in(scenario.control.clone(), model, scenario.settle, base_dir)?;
    let mut sys = RoverSystem::new(plant, ground, control);
    y.resize(sys.dim(), 0.0);
    sys.roll_spins(0.0, &mut y);
    Ok((sys, y))
}

/// The sensors' period of a scenario with `[sensors]`: the run lands on
/// their instants whether or not their readings are written, so that its
/// rows do not depend on where it is run from.
pub(crate) fn sensor_period(scenario: &Scenario) -> Option<f64> {
    scenario.sensors.as_ref().map(|s| 1.0 / s.rate)
}

/// The readings of a scenario's sensors at each sensor instant, written
/// to the sensor log: the simulator and the buffers of the truth, sized
/// once.
struct SensorRecorder<W: Write> {
    sim: SensorSimulator,
    sample: SensorSample,
    /// ẏ at the instant.
    dy: Vec<f64>,
    /// Each wheel's spin rate at the instant.
    rates: Vec<f64>,
    gravity: f64,
    n: usize,
    log: SensorLogWriter<W>,
}

impl<W: Write> SensorRecorder<W> {
    fn new(config: &SensorConfig, model: &Model, dim: usize, out: W) -> Result<Self, SetupError> {
        let (k, m) = (model.wheels.len(), model.m());
        let sim = SensorSimulator::new(config, k, m).map_err(|e| SetupError::Unsupported {
            field: e.field,
            message: e.message,
        })?;
        Ok(Self {
            sample: sim.new_sample(),
            sim,
            dy: vec![0.0; dim],
            rates: vec![0.0; k],
            gravity: model.gravity,
            n: model.dof(),
            log: SensorLogWriter::new(out, config, k, m)?,
        })
    }

    /// The readings at `(t, y)`: one right-hand side gives ẇ, the wheels'
    /// spin rates and the commands there. Allocates nothing.
    fn record<P: Plant, H: rover_dynamics::HeightField>(
        &mut self,
        t: f64,
        y: &[f64],
        sys: &mut RoverSystem<P, H>,
    ) -> Result<(), RunError> {
        sys.evaluate_at(t, y, &mut self.dy)?;
        sys.wheel_spin_rates(y, &mut self.rates);
        let n = self.n;
        let truth = Truth {
            t,
            x: &y[..n],
            w: &y[n..2 * n],
            w_dot: &self.dy[n..2 * n],
            wheel_rates: &self.rates,
            torques: sys.torques(),
            steering: sys.steering(),
            gravity: self.gravity,
        };
        let failed = |message: String| RunError::Output {
            t,
            message: format!("sensors.csv: {message}"),
        };
        self.sim
            .sample_into(&truth, &mut self.sample)
            .map_err(|e| failed(e.to_string()))?;
        self.log
            .write(&self.sample)
            .map_err(|e| failed(e.to_string()))
    }
}

/// The driver's options of a scenario: its duration, output interval and
/// roll-over limit.
pub(crate) fn run_options(scenario: &Scenario) -> RunOptions {
    RunOptions {
        duration: scenario.duration,
        output_step: 1.0 / scenario.output_rate,
        rollover_limit: scenario.rollover_limit_deg.to_radians(),
    }
}

/// Run `scenario` with `plant` (whose model is `model`, named `name`),
/// writing the CSV to `csv`. `progress(t)` is called at every output row.
/// The readings of the scenario's `[sensors]` are not written
/// ([`simulate_with_outputs`] writes them), but the run lands on their
/// instants all the same: its rows are those of the run that writes them.
///
/// A plant that does not fit the model (another number of coordinates or
/// wheels, another total mass) is a [`SetupError::Mismatch`] naming what
/// differs: the ground and the controllers read the model, so a run of
/// one rover's plant with another's model would be neither.
pub fn simulate<P: Plant, W: Write>(
    plant: P,
    model: &Model,
    name: &str,
    scenario: &Scenario,
    base_dir: &Path,
    csv: W,
    interrupt: &AtomicBool,
    progress: impl FnMut(f64),
) -> Result<Summary, SetupError> {
    simulate_with_outputs(
        plant,
        model,
        name,
        scenario,
        base_dir,
        csv,
        None::<std::io::Sink>,
        None,
        interrupt,
        progress,
    )
}

/// [`simulate`], writing the readings of the scenario's `[sensors]` to
/// `sensors` at each sensor instant (t = 0 first; the columns of
/// [`rover_estimate::sensors::columns`]), when both are given, and handing
/// each row also to `rows` (the MCAP log): the same values as the CSV's,
/// computed once. A log or sink that cannot be written stops the run as
/// failed, like the CSV; a sink is finished (given the ground) also after
/// a failure.
pub fn simulate_with_outputs<P: Plant, W: Write, S: Write>(
    plant: P,
    model: &Model,
    name: &str,
    scenario: &Scenario,
    base_dir: &Path,
    csv: W,
    sensors: Option<S>,
    mut rows: Option<&mut dyn RowSink>,
    interrupt: &AtomicBool,
    mut progress: impl FnMut(f64),
) -> Result<Summary, SetupError> {
    let mut plant = plant;
    let label = plant_label(&plant);
    let differences = rover_runtime::described::plant_differences(&mut plant, model);
    if !differences.is_empty() {
        return Err(rover_runtime::described::Mismatch { differences }.into());
    }
    if scenario.fidelity == FidelityLevel::QuasiStatic {
        return quasi_static_run(
            (model, name, label),
            scenario,
            base_dir,
            csv,
            rows,
            interrupt,
            progress,
        );
    }
    let (mut sys, mut y) = system_of(plant, model, scenario, base_dir)?;
    let kinematic_radius = sys.control.kinematic_radius(scenario.duration);
    if scenario.profile {
        sys.enable_profile();
    }
    let mut integ = scenario.integrator.build(sys.dim())?;
    let n = model.dof();
    let k = model.wheels.len();
    let columns = Columns::on_ground(model.m(), k, !sys.spin_range().is_empty());
    let mut writer = CsvWriter::new(csv, &columns)?;
    if let Some(r) = rows.as_deref_mut() {
        r.start(&columns).map_err(sink_error)?;
    }
    let mut recorder = match (&scenario.sensors, sensors) {
        (Some(config), Some(out)) => Some(SensorRecorder::new(config, model, sys.dim(), out)?),
        _ => None,
    };
    let opts = run_options(scenario);
    let rest_x: Vec<f64> = model.rest_wheel_centres().iter().map(|u| u[0]).collect();
    let mut log = RunLog::new(scenario.settle, model.dof(), k)
        .with_axles(axles_by_rest_x(&rest_x))
        .with_soil(columns.names(), k);
    let started = Instant::now();
    let outcome = run_with_sensors(
        &mut sys,
        &mut integ,
        &mut y,
        &opts,
        sensor_period(scenario),
        interrupt,
        |row| {
            let s = row.system;
            let inputs = RowInputs::of_system(s, row.t, row.y, s.control.speed_setpoint(row.t));
            let values = writer.write(&inputs)?;
            if let Some(r) = rows.as_deref_mut() {
                r.row(values)?;
            }
            log.record(values, s.reports().iter().map(|r| r.deep));
            progress(row.t);
            Ok(())
        },
        |t, y, sys| match &mut recorder {
            Some(r) => r.record(t, y, sys),
            None => Ok(()),
        },
    );
    let wall = started.elapsed().as_secs_f64();
    writer.into_inner()?;
    if let Some(r) = rows {
        r.finish(sys.ground.as_ref().map(|g| &g.terrain))
            .map_err(sink_error)?;
    }
    if let Some(r) = recorder {
        r.log.into_inner()?;
    }
    let (status, error) = match &outcome.stop {
        Stop::Completed => (Status::Completed, None),
        Stop::Interrupted { t } => (
            Status::Interrupted,
            Some(format!("interrupted by the user at t = {t:.3} s")),
        ),
        Stop::Failed(e @ RunError::Embedded { .. }) => (Status::Embedded, Some(e.to_string())),
        Stop::Failed(e) => (Status::Failed, Some(with_contact_hint(e, scenario))),
    };
    let stats = integ.stats();
    let path_deviation = path_deviation(&log, scenario);
    let mut summary = log.summary(
        columns.names(),
        n,
        RunEnd {
            rover: name.to_string(),
            status,
            error,
            duration: scenario.duration,
            t_end: outcome.t,
            kinematic_radius,
            wall_time_s: wall,
            integrator: integ.name().to_string(),
            plant: label,
            rhs_evals: stats.rhs_evals,
            steps: stats.steps,
            rejected_steps: stats.rejected_steps,
            jacobian_evals: stats.jacobian_evals,
            lu_decompositions: stats.lu_decompositions,
        },
    );
    summary.path_deviation = path_deviation;
    // The ruts as the run left them, also after a failure: the rows up to
    // it pressed them.
    summary.rut_grid = sys
        .ground
        .as_ref()
        .and_then(|g| crate::output::RutGrid::of(g.ruts()?.map(), &g.terrain));
    summary.ruts = summary.rut_grid.as_ref().map(|g| g.summary().clone());
    summary.profile = sys
        .profile()
        .map(|p| rover_runtime::sim::Profile::new(&p, wall));
    Ok(summary)
}

/// The error of a failed run, with a hint when the tracking contact search
/// is the likely cause: it follows one patch per wheel, which jumps where a
/// wheel meets the ground at two places (docs/TERRAIN.md), and step-size
/// control cannot follow a jump. The default search, bounded, finds every
/// patch.
fn with_contact_hint(e: &RunError, scenario: &Scenario) -> String {
    let text = e.to_string();
    match e {
        RunError::Integration {
            step_control: true, ..
        } if scenario.contact.method == ContactMethod::Tracked => format!(
            "{text}; the tracked contact search follows one patch per wheel and jumps where a wheel meets the ground at two places: the bounded search (`[contact] method = \"bounded\"`, the default) finds every patch and keeps the forces continuous there"
        ),
        _ => text,
    }
}

/// G's distance from the path its heading hold follows, over the output
/// instants after settling; `None` without one.
fn path_deviation(log: &RunLog, scenario: &Scenario) -> Option<crate::output::PathDeviation> {
    let rover_runtime::control::Steering::Heading(h) = &scenario.control.steering else {
        return None;
    };
    if !h.follows_a_path() {
        return None;
    }
    let d: Vec<f64> = log
        .track()
        .map(|(t, p)| h.deviation(t - scenario.settle, p))
        .collect();
    let last = *d.last()?;
    Some(crate::output::PathDeviation {
        max_m: d.iter().fold(0.0, |m: f64, v| m.max(*v)),
        rms_m: (d.iter().map(|v| v * v).sum::<f64>() / d.len() as f64).sqrt(),
        final_m: last,
    })
}

/// The horizontal motion a quasi-static run imposes: (t, X, Y, ψ) samples.
fn imposed_path(
    model: &Model,
    scenario: &Scenario,
    base_dir: &Path,
    y0: &[f64],
    times: &[f64],
) -> Result<Vec<[f64; 3]>, SetupError> {
    if let Some(file) = &scenario.path_from {
        let path = base_dir.join(file);
        let text = rover_files::read_text(&path, rover_files::Limit::Data).map_err(|e| {
            SetupError::Path(format!(
                "{}: cannot read it: {e}; give the CSV of a run (`run.csv`)",
                path.display()
            ))
        })?;
        let mut lines = text.lines();
        let header: Vec<&str> = lines.next().unwrap_or("").split(',').collect();
        let col = |name: &str| {
            header
                .iter()
                .position(|h| *h == name)
                .ok_or_else(|| SetupError::Path(format!("{}: no column `{name}`", path.display())))
        };
        let (ct, cx, cy, cp) = (col("t")?, col("X")?, col("Y")?, col("psi")?);
        let mut rows: Vec<[f64; 4]> = Vec::new();
        for (i, l) in lines.enumerate() {
            let v: Vec<f64> = l
                .split(',')
                .map(|c| c.parse().unwrap_or(f64::NAN))
                .collect();
            let r = [ct, cx, cy, cp].map(|c| v.get(c).copied().unwrap_or(f64::NAN));
            if r.iter().any(|x| !x.is_finite()) {
                return Err(SetupError::Path(format!(
                    "{}:{}: not a number in t, X, Y or psi",
                    path.display(),
                    i + 2
                )));
            }
            if let Some(prev) = rows.last()
                && r[0] <= prev[0]
            {
                return Err(SetupError::Path(format!(
                    "{}:{}: t = {} does not follow the previous row's t = {}: the times of a path must increase",
                    path.display(),
                    i + 2,
                    r[0],
                    prev[0]
                )));
            }
            rows.push(r);
        }
        if rows.len() < 2 {
            return Err(SetupError::Path(format!(
                "{}: fewer than two rows",
                path.display()
            )));
        }
        return Ok(times
            .iter()
            .map(|&t| {
                let k = rows.partition_point(|r| r[0] <= t).clamp(1, rows.len() - 1);
                let (a, b) = (rows[k - 1], rows[k]);
                let s = ((t - a[0]) / (b[0] - a[0])).clamp(0.0, 1.0);
                [
                    a[1] + s * (b[1] - a[1]),
                    a[2] + s * (b[2] - a[2]),
                    a[3] + s * (b[3] - a[3]),
                ]
            })
            .collect());
    }
    if matches!(
        scenario.control.steering,
        rover_runtime::control::Steering::Slip { .. }
            | rover_runtime::control::Steering::Heading(_)
    ) || scenario.control.commands.is_some()
    {
        return Err(SetupError::Path(
            "a quasi-static run with slip steering, heading hold or open-loop commands needs `path_from = \"<run.csv>\"`: the path of a dynamic run of the same scenario".into(),
        ));
    }
    // The kinematic path: G moves with body velocity [V, −ω·x_c], ω = κ·V.
    let control = Controller::new_in(scenario.control.clone(), model, scenario.settle, base_dir)?;
    let mut pose = [y0[0], y0[1], y0[5]];
    let mut out = Vec::with_capacity(times.len());
    let mut t = 0.0;
    for &target in times {
        while t < target - 1e-12 {
            let h = (target - t).min(1e-3);
            let rate = |t: f64, p: [f64; 3]| {
                let v = control.speed_setpoint(t);
                let (kappa, xc) = control.curvature(t);
                let om = kappa * v;
                let (s, c) = p[2].sin_cos();
                [c * v + s * om * xc, s * v - c * om * xc, om]
            };
            let k1 = rate(t, pose);
            let mid = [0, 1, 2].map(|i| pose[i] + 0.5 * h * k1[i]);
            let k2 = rate(t + 0.5 * h, mid);
            pose = [0, 1, 2].map(|i| pose[i] + h * k2[i]);
            t += h;
        }
        out.push(pose);
    }
    Ok(out)
}

/// Level 4: static equilibria along the imposed path, one per output instant.
fn quasi_static_run<W: Write>(
    (model, name, label): (&Model, &str, String),
    scenario: &Scenario,
    base_dir: &Path,
    csv: W,
    mut rows: Option<&mut dyn RowSink>,
    interrupt: &AtomicBool,
    mut progress: impl FnMut(f64),
) -> Result<Summary, SetupError> {
    if scenario.soft() {
        return Err(SetupError::Unsupported {
            field: "fidelity",
            message: "the quasi-static level stands the rover on rigid ground: it has no wheel spin for a soil's slip\n  = help: run a soil at the \"full\", \"simplified\" or \"linearized\" level, or remove `soil` from [terrain]".into(),
        });
    }
    let terrain = scenario.terrain.build(base_dir)?;
    let y0 = initial_state(model, scenario, Some(&terrain))?;
    let n = model.dof();
    let k = model.wheels.len();
    let steps = (scenario.duration * scenario.output_rate).ceil() as usize;
    let mut times: Vec<f64> = (0..=steps)
        .map(|i| i as f64 / scenario.output_rate)
        .take_while(|&t| t < scenario.duration - 1e-12 * (1.0 + scenario.duration))
        .collect();
    // The end of the run is always a row.
    times.push(scenario.duration);
    let poses = imposed_path(model, scenario, base_dir, &y0, &times)?;
    let control = Controller::new_in(scenario.control.clone(), model, scenario.settle, base_dir)?;
    let kinematic_radius = control.kinematic_radius(scenario.duration);
    let mut q0 = vec![y0[2], y0[3], y0[4]];
    q0.extend_from_slice(&y0[6..n]);
    let mut solver = rover_runtime::quasi_static::QuasiStatic::new(
        model,
        &terrain,
        rover_dynamics::contact::MeridionalContact {
            sampling: scenario.contact.sampling(),
        },
        q0,
    );
    let columns = Columns::new(model.m(), k);
    let mut writer = CsvWriter::new(csv, &columns)?;
    if let Some(r) = rows.as_deref_mut() {
        r.start(&columns).map_err(sink_error)?;
    }
    let started = Instant::now();
    let mut log = RunLog::imposed(scenario.settle, k);
    let mut stop = (Status::Completed, None, scenario.duration);
    let mut normals = vec![0.0; k];
    let mut wheels = vec![rover_dynamics::plant::WheelState::default(); k];
    // The imposed motion's contact: normal forces only, at the contact points.
    let mut reports = vec![rover_dynamics::wheel_ground::WheelReport::default(); k];
    let mut plant = rover_runtime::GenericPlant::new(model.clone())?;
    let zeros = vec![0.0; n];
    // No motion, so no torques and no steering.
    let per_wheel_zeros = vec![0.0; k];
    // The first solve starts standing on the terrain's plane under the
    // wheels; later ones from the previous solution.
    if let Some(&first) = poses.first() {
        solver.align(first)?;
    }
    for (&t, &pose) in times.iter().zip(&poses) {
        if interrupt.load(std::sync::atomic::Ordering::Relaxed) {
            stop = (
                Status::Interrupted,
                Some(format!("interrupted by the user at t = {t:.3} s")),
                t,
            );
            break;
        }
        if let Err(e) = solver
            .solve(pose)
            .and_then(|_| solver.normal_forces(pose, &mut normals))
        {
            stop = (Status::Failed, Some(format!("t = {t:.3} s: {e}")), t);
            break;
        }
        let x = solver.coordinates(pose, &solver.q);
        use rover_dynamics::plant::Plant;
        plant.wheels(&x, &zeros, &per_wheel_zeros, &mut wheels);
        for ((report, h), fz) in reports
            .iter_mut()
            .zip(solver.contact_points())
            .zip(&normals)
        {
            report.point = *h;
            report.normal = *fz;
        }
        let inputs = RowInputs {
            t,
            x: &x,
            w: &zeros,
            wheels: &wheels,
            reports: &reports,
            spins: &[],
            torques: &per_wheel_zeros,
            steering: &per_wheel_zeros,
            neutrals: control.neutrals(),
            speed_setpoint: control.speed_setpoint(t),
        };
        let values = writer.write(&inputs)?;
        if let Some(r) = rows.as_deref_mut() {
            r.row(values)?;
        }
        log.record(values, std::iter::empty());
        progress(t);
    }
    writer.into_inner()?;
    if let Some(r) = rows {
        r.finish(Some(&terrain)).map_err(sink_error)?;
    }
    let wall = started.elapsed().as_secs_f64();
    let (status, error, t_end) = stop;
    Ok(log.summary(
        columns.names(),
        n,
        RunEnd {
            rover: name.to_string(),
            status,
            error,
            duration: scenario.duration,
            t_end,
            kinematic_radius,
            wall_time_s: wall,
            integrator: "quasi-static newton".into(),
            plant: label,
            rhs_evals: solver.residual_evals,
            steps: solver.iterations,
            rejected_steps: 0,
            // Each Newton iteration differentiates the residual and solves
            // with it once.
            jacobian_evals: solver.iterations,
            lu_decompositions: solver.iterations,
        },
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn failure(step_control: bool) -> RunError {
        RunError::Integration {
            t: 5.0,
            message: "step size 5e-11 s is below the minimum step 1e-10 s".into(),
            step_control,
        }
    }

    #[test]
    fn a_tracked_run_that_step_control_gave_up_on_points_to_the_default_search() {
        let path = Path::new("s.toml");
        let tracked =
            Scenario::parse("duration = 1.0\n[contact]\nmethod = \"tracked\"\n", path).unwrap();
        let default = Scenario::parse("duration = 1.0\n", path).unwrap();
        let hinted = with_contact_hint(&failure(true), &tracked);
        assert!(
            hinted.starts_with("the run stopped at t = 5.000000 s: step size")
                && hinted.contains("method = \"bounded\""),
            "{hinted}"
        );
        // Not for the default search, nor for failures of another kind.
        for (e, s) in [(failure(true), &default), (failure(false), &tracked)] {
            assert_eq!(with_contact_hint(&e, s), e.to_string());
        }
    }
}
