//! Runs of a rover from a scenario: the scenario file (`[terrain]`,
//! `[initial]`, `[control]`, `[contact]`, `[integrator]`, `[sensors]`),
//! the whole run and its outputs (CSV, summary, plots' data, the sensor
//! log), runs step by step, the linearization about a steady state, and
//! [`Simulation`], a run assembled in Rust.
//!
//! # A rover declared in Rust
//!
//! `#[derive(Rover)]` (crate `rover-derive`) turns a description into a
//! generated plant that carries the description with it. [`Simulation`]
//! runs it: the model that the terrain contact and the controllers read is
//! parsed from the plant's own description, so one declaration gives both
//! and they cannot disagree. `RoverDescription` (rover-runtime) gives the model and what
//! `rover check` prints for the rover.
//!
//! ```
//! use rover_derive::Rover;
//! use rover_runtime::RoverDescription;
//! use rover_runtime::control::Steering;
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
//! // What `rover check` prints: masses, fits and their errors, rest geometry.
//! assert!(Swing4::report()?.starts_with("rover `swing4`: 10 DOF"));
//! // A run, from the derived type alone.
//! let summary = Simulation::new(Swing4::plant())
//!     .terrain(TerrainConfig::random(0.1))
//!     .settle(1.0)
//!     .speed(0.1)
//!     .steering(Steering::slip(0.05))
//!     .run(2.0)?;
//! println!("{:?}", summary.final_state);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
#![warn(missing_docs)]

pub mod columns;
pub mod estimate;
pub mod ground;
pub mod linearize;
mod locate;
pub mod output;
pub mod prepare;
pub mod scenario;
pub mod sensor_log;
pub mod simulate;
mod simulation;
mod stepper;
pub mod sweep;
pub mod truth_log;

pub use sensor_log::read_sensor_log;
pub use simulation::{Simulation, SimulationError};
pub use stepper::Stepper;
