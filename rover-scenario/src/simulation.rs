//! A run assembled in Rust: the same run as a scenario file's, with the
//! scenario's tables as typed builder calls.
//!
//! [`Simulation`] fills a [`Scenario`] and hands it to
//! [`simulate`](crate::simulate::simulate()), the function `rover simulate`
//! runs: the same defaults, the same checks, the same errors naming the
//! field, the same [`Summary`]. With a rover declared by `#[derive(Rover)]`
//! the plant alone is enough: the model the terrain contact and the
//! controllers read comes from the plant's own description, so the two
//! cannot disagree.
//!
//! ```
//! use rover_derive::Rover;
//! use rover_scenario::Simulation;
//! use rover_runtime::terrain::TerrainConfig;
//!
//! #[derive(Rover)]
//! #[rover(
//!     name = "swing4", gravity = 1.62,
//!     body = { mass = 30.0, inertia = [0.7, 0.9, 1.5] },
//!     wheel_defaults = { mass = 0.6, radius = 0.09, stiffness = 4000.0, damping = 300.0,
//!         mu_x = 0.5, mu_y = 0.5, cornering_stiffness = 50.0, max_torque = 1.29 },
//!     suspension = [
//!         { name = "fl", kind = "longitudinal_swing_arm", pivot = [0.18, 0.2, -0.01], length = 0.2,
//!           coordinate = { rest_deg = -17.2, min_deg = -60.0, max_deg = -2.0, stiffness = 5.0, damping = 3.5 } },
//!         { name = "fr", kind = "longitudinal_swing_arm", pivot = [0.18, -0.2, -0.01], length = 0.2,
//!           coordinate = { rest_deg = -17.2, min_deg = -60.0, max_deg = -2.0, stiffness = 5.0, damping = 3.5 } },
//!         { name = "rl", kind = "longitudinal_swing_arm", pivot = [-0.22, 0.2, -0.01], length = 0.2,
//!           coordinate = { rest_deg = 17.2, min_deg = 2.0, max_deg = 60.0, stiffness = 5.0, damping = 3.5 } },
//!         { name = "rr", kind = "longitudinal_swing_arm", pivot = [-0.22, -0.2, -0.01], length = 0.2,
//!           coordinate = { rest_deg = 17.2, min_deg = 2.0, max_deg = 60.0, stiffness = 5.0, damping = 3.5 } },
//!     ],
//!     wheel = [
//!         { name = "fl", suspension = "fl" }, { name = "fr", suspension = "fr" },
//!         { name = "rl", suspension = "rl" }, { name = "rr", suspension = "rr" },
//!     ],
//! )]
//! struct Swing4;
//!
//! let summary = Simulation::new(Swing4::plant())
//!     .terrain(TerrainConfig::random(0.1))
//!     .settle(1.0)
//!     .speed(0.1)
//!     .run(2.0)?;
//! assert!(summary.complete);
//! # Ok::<(), rover_scenario::SimulationError>(())
//! ```

use std::io::Write;
use std::path::PathBuf;
use std::sync::atomic::AtomicBool;

use rover_dynamics::described::Described;
use rover_dynamics::plant::Plant;
use rover_spec::{Spec, SpecError};

use crate::output::{Status, Summary};
use crate::scenario::{ContactConfig, FieldError, InitialState, Scenario};
use crate::simulate::{SetupError, simulate};
use rover_integrate::IntegratorConfig;
use rover_runtime::control::{ControllerConfig, SpeedConfig, Steering};
use rover_runtime::described::{Mismatch, RoverDescription, model_differences};
use rover_terrain::TerrainConfig;

/// Why a [`Simulation`] did not run to its end.
#[derive(Debug, thiserror::Error)]
pub enum SimulationError {
    /// The plant's description does not load (only with two versions of
    /// `rover-spec` in one build: the derive validated it).
    #[error("{0}")]
    Description(#[from] SpecError),
    /// The plant and the model given with it are of different rovers.
    #[error("{0}")]
    Mismatch(#[from] Mismatch),
    /// A setting is out of range; the message names the field as a
    /// scenario file would write it.
    #[error("{0}")]
    Scenario(#[from] FieldError),
    /// The run could not start: the terrain, the controllers, the
    /// integrator or the initial state do not fit the rover.
    #[error("{0}")]
    Setup(#[from] SetupError),
    /// The run started but stopped before its end (an integration failure,
    /// a roll-over); the summary holds what was computed and why it stopped.
    #[error("the run stopped at t = {:.3} s: {}", .0.t_end, .0.error.as_deref().unwrap_or("stopped"))]
    Incomplete(Box<Summary>),
}

/// A run of one rover, assembled call by call; [`Simulation::run`] runs it.
///
/// Every setting has the default a scenario file has when it leaves the
/// table out: flat ground, no motor torque, no steering, BDF at its default
/// tolerances (rtol 1e-4, absolute tolerances per state component),
/// 20 output rows per second, the rover at rest at the origin with its
/// wheels on the ground. Nothing is checked until `run`, which reports the
/// first problem.
pub struct Simulation<P> {
    plant: P,
    spec: Result<Spec, SimulationError>,
    scenario: Scenario,
    base_dir: PathBuf,
    csv: Box<dyn Write>,
}

impl<P: Plant + Described> Simulation<P> {
    /// A run of the plant of a rover declared with `#[derive(Rover)]`, the
    /// model taken from the plant's own description.
    pub fn new(plant: P) -> Self {
        Self::assemble(plant, P::spec().map_err(SimulationError::from))
    }

    /// A run of a derived plant with a model loaded separately (a TOML
    /// file, say): `run` refuses it with [`SimulationError::Mismatch`],
    /// naming every field that differs, unless the two are the same rover.
    pub fn with_spec(plant: P, spec: Spec) -> Self {
        let checked = P::spec().map_err(SimulationError::from).and_then(|own| {
            let differences = model_differences(&own.model, &own, &spec.model);
            if differences.is_empty() {
                Ok(spec)
            } else {
                Err(Mismatch { differences }.into())
            }
        });
        Self::assemble(plant, checked)
    }
}

impl<P: Plant> Simulation<P> {
    /// A run of any plant with its model: the generic plant
    /// ([`rover_runtime::GenericPlant`]), a built-in rover's generated one, a
    /// hand-written one. Without a description to compare, `run` checks
    /// what the plant itself shows: its sizes and its total mass.
    pub fn from_parts(plant: P, spec: Spec) -> Self {
        Self::assemble(plant, Ok(spec))
    }

    fn assemble(plant: P, spec: Result<Spec, SimulationError>) -> Self {
        Simulation {
            plant,
            spec,
            scenario: Scenario::with_duration(1.0),
            base_dir: PathBuf::from("."),
            csv: Box::new(std::io::sink()),
        }
    }

    /// Every setting of a scenario at once, as read by
    /// [`Scenario::load`]; later calls change single settings, and `run`
    /// sets the duration.
    pub fn scenario(mut self, scenario: Scenario) -> Self {
        self.scenario = scenario;
        self
    }

    /// The ground (`[terrain]`; default flat at Z = 0).
    pub fn terrain(mut self, terrain: TerrainConfig) -> Self {
        self.scenario.terrain.shape = terrain;
        self
    }

    /// The speed loop (`[control.speed]`): a constant set-point in m/s
    /// (`.speed(0.1)`) or a whole [`SpeedConfig`].
    pub fn speed(mut self, speed: impl Into<SpeedConfig>) -> Self {
        self.scenario.control.speed = Some(speed.into());
        self
    }

    /// Steering (`[control.steering]`; default none).
    pub fn steering(mut self, steering: Steering) -> Self {
        self.scenario.control.steering = steering;
        self
    }

    /// All the controllers at once (`[control]`), replacing `speed` and
    /// `steering`.
    pub fn control(mut self, control: ControllerConfig) -> Self {
        self.scenario.control = control;
        self
    }

    /// The integrator (`[integrator.<method>]`; default BDF of orders 1–2
    /// at its default tolerances, [`crate::scenario::default_integrator`]).
    pub fn integrator(mut self, integrator: IntegratorConfig) -> Self {
        self.scenario.integrator = integrator;
        self
    }

    /// Settling time \[s\]: the commands stay at zero until then, so the
    /// rover comes to rest on its wheels first (default 0).
    pub fn settle(mut self, seconds: f64) -> Self {
        self.scenario.settle = seconds;
        self
    }

    /// Output rows per second (default 20): the CSV's rows and the
    /// summary's samples.
    pub fn output_rate(mut self, hz: f64) -> Self {
        self.scenario.output_rate = hz;
        self
    }

    /// The initial state (`[initial]`; default at rest at the origin,
    /// wheels touching the ground).
    pub fn initial(mut self, initial: InitialState) -> Self {
        self.scenario.initial = initial;
        self
    }

    /// Contact search and wheel law (`[contact]`).
    pub fn contact(mut self, contact: ContactConfig) -> Self {
        self.scenario.contact = contact;
        self
    }

    /// Where relative paths (terrain files, command files) are read from
    /// (default the working directory).
    pub fn base_dir(mut self, dir: impl Into<PathBuf>) -> Self {
        self.base_dir = dir.into();
        self
    }

    /// Where the CSV goes (`rover simulate`'s `run.csv`, same columns);
    /// by default nowhere.
    pub fn csv(mut self, out: impl Write + 'static) -> Self {
        self.csv = Box::new(out);
        self
    }

    /// Run `duration` seconds of simulated time, settling included.
    ///
    /// A run that completes gives its summary (final state, distance,
    /// extremes, cost); one that stops early is
    /// [`SimulationError::Incomplete`] with the summary of what it
    /// computed.
    pub fn run(self, duration: f64) -> Result<Summary, SimulationError> {
        let spec = self.spec?;
        let mut scenario = self.scenario;
        scenario.duration = duration;
        scenario.validate()?;
        let summary = simulate(
            self.plant,
            &spec.model,
            &spec.name,
            &scenario,
            &self.base_dir,
            self.csv,
            &AtomicBool::new(false),
            |_| {},
        )?;
        match summary.status {
            Status::Completed => Ok(summary),
            _ => Err(SimulationError::Incomplete(Box::new(summary))),
        }
    }
}
