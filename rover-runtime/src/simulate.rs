//! A whole run from a scenario: build the pieces, place the rover, run,
//! write the CSV, summarize (issue 5 item 3; the CLI adds plots and the
//! progress bar).

use std::io::Write;
use std::path::Path;
use std::sync::atomic::AtomicBool;
use std::time::Instant;

use rover_dynamics::Model;
use rover_dynamics::attitude::Attitude;
use rover_dynamics::plant::Plant;

use crate::control::Controller;
use crate::ground::Ground;
use crate::integrate::{Integrator, OdeSystem};
use crate::output::{CsvWriter, Status, Summary, fit_circle, header};
use crate::scenario::Scenario;
use crate::sim::{RoverSystem, RunOptions, Stop, run};
use crate::terrain::{HeightField, Terrain};

/// A run that could not start: the scenario does not fit the rover, or a
/// piece could not be built.
#[derive(Debug, thiserror::Error)]
pub enum SetupError {
    /// The terrain could not be built or loaded.
    #[error("{0}")]
    Terrain(#[from] crate::terrain::TerrainError),
    /// The controller does not fit the rover.
    #[error("{0}")]
    Control(#[from] crate::control::ControlError),
    /// The integrator's parameters are invalid.
    #[error("{0}")]
    Integrator(#[from] crate::integrate::ConfigError),
    /// The initial state does not fit the rover.
    #[error("initial.{field}: {message}")]
    Initial {
        /// The field.
        field: &'static str,
        /// What is wrong and how to fix it.
        message: String,
    },
    /// The rover starts off the terrain map.
    #[error("the rover starts off the terrain: {0}")]
    OffMap(crate::terrain::OffMap),
    /// The CSV could not be started.
    #[error("cannot write the CSV: {0}")]
    Io(#[from] std::io::Error),
}

impl SetupError {
    /// The scenario field the error is about, as a dotted path, when it has one.
    pub fn field_path(&self) -> Option<String> {
        match self {
            SetupError::Terrain(crate::terrain::TerrainError::Parameter { name, .. }) => {
                Some(format!("terrain.{name}"))
            }
            SetupError::Control(e) => Some(format!("control.{}", e.field)),
            SetupError::Integrator(e) => Some(format!("integrator.{}.{}", e.method, e.field)),
            SetupError::Initial { field, .. } => Some(format!("initial.{field}")),
            _ => None,
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
        (Some(z), _) => z,
        (None, None) => 0.0,
        (None, Some(t)) => ground_contact_height(model, &y[..n], t)?,
    };
    Ok(y)
}

/// Z of G such that the lowest wheel just touches the ground below it.
fn ground_contact_height(model: &Model, x: &[f64], terrain: &Terrain) -> Result<f64, SetupError> {
    let r = Attitude::new(x[3], x[4], x[5]).rotation();
    let mut z = f64::NEG_INFINITY;
    for w in &model.wheels {
        let u = model.bodies[w.body].position.value(&x[6..]);
        let p = [0, 1, 2].map(|k| r[k][0] * u[0] + r[k][1] * u[1] + r[k][2] * u[2]);
        let g = terrain
            .height(x[0] + p[0], x[1] + p[1])
            .map_err(SetupError::OffMap)?;
        z = z.max(g + w.radius - p[2]);
    }
    Ok(z)
}

/// Run `scenario` with `plant` (whose model is `model`, named `name`),
/// writing the CSV to `csv`. `progress(t)` is called at every output row.
pub fn simulate<P: Plant, W: Write>(
    plant: P,
    model: &Model,
    name: &str,
    scenario: &Scenario,
    base_dir: &Path,
    csv: W,
    interrupt: &AtomicBool,
    mut progress: impl FnMut(f64),
) -> Result<Summary, SetupError> {
    let terrain = if scenario.free_flight {
        None
    } else {
        Some(scenario.terrain.build(base_dir)?)
    };
    let mut y = initial_state(model, scenario, terrain.as_ref())?;
    let ground = terrain.map(|t| {
        Ground::new(
            t,
            model,
            scenario.contact.method,
            scenario.contact.sampling(),
            scenario.contact.law,
        )
    });
    let control = Controller::new(scenario.control.clone(), model, scenario.settle)?;
    let kinematic_radius = control.kinematic_radius(scenario.duration);
    let mut sys = RoverSystem::new(plant, ground, control);
    let mut integ = scenario.integrator.build(sys.dim())?;
    let n = model.dof();
    let k = model.wheels.len();
    let cols = header(model.m(), k);
    let mut writer = CsvWriter::new(csv, &cols)?;
    let opts = RunOptions {
        duration: scenario.duration,
        output_step: 1.0 / scenario.output_rate,
        rollover_limit: scenario.rollover_limit_deg.to_radians(),
    };
    let mut path = Vec::new();
    let mut deep = vec![false; k];
    let mut last = Vec::new();
    let started = Instant::now();
    let outcome = run(&mut sys, &mut integ, &mut y, &opts, interrupt, |row| {
        let s = row.system;
        let v = writer.row();
        v.push(row.t);
        v.extend_from_slice(&row.y[..2 * n]);
        for w in s.wheel_states() {
            v.extend_from_slice(&w.centre);
        }
        for r in s.reports() {
            v.extend_from_slice(&r.point);
            v.extend_from_slice(&[r.normal, r.drawbar, r.lateral]);
        }
        v.extend_from_slice(s.torques());
        v.extend_from_slice(s.steering());
        v.push(s.control.speed_setpoint(row.t));
        last.clone_from(v);
        for (d, r) in deep.iter_mut().zip(s.reports()) {
            *d |= r.deep;
        }
        if row.t >= scenario.settle {
            path.push([row.y[0], row.y[1]]);
        }
        progress(row.t);
        writer.finish_row()
    });
    let wall = started.elapsed().as_secs_f64();
    writer.into_inner()?;
    let (status, error) = match &outcome.stop {
        Stop::Completed => (Status::Completed, None),
        Stop::Interrupted { t } => (
            Status::Interrupted,
            Some(format!("interrupted by the user at t = {t:.3} s")),
        ),
        Stop::Failed(e) => (Status::Failed, Some(e.to_string())),
    };
    let stats = integ.stats();
    Ok(Summary {
        rover: name.to_string(),
        complete: status == Status::Completed,
        status,
        error,
        duration: scenario.duration,
        t_end: outcome.t,
        final_state: cols
            .iter()
            .cloned()
            .zip(last.iter().copied())
            .take(1 + 2 * n)
            .collect(),
        max_roll_deg: outcome.max_roll.to_degrees(),
        max_pitch_deg: outcome.max_pitch.to_degrees(),
        turning_circle: fit_circle(&path),
        kinematic_radius,
        deep_penetration_wheels: deep
            .iter()
            .enumerate()
            .filter(|(_, d)| **d)
            .map(|(i, _)| i + 1)
            .collect(),
        wall_time_s: wall,
        real_time_factor: if wall > 0.0 {
            outcome.t / wall
        } else {
            f64::INFINITY
        },
        integrator: integ.name().to_string(),
        rhs_evals: stats.rhs_evals,
        steps: stats.steps,
        rejected_steps: stats.rejected_steps,
    })
}
