//! The rover runtime: everything around the plant in one step of a run —
//! the generic plant, the wheels' contact with the ground, the wheel laws,
//! the controllers and the simulation loop (`sim`); the integrators come
//! from `rover-integrate`, the terrains from `rover-terrain`, and runs from
//! a scenario (the file, the whole run, its outputs) from `rover-scenario`.
//!
//! A rig assembles a run from these pieces: a plant (generated, or
//! [`GenericPlant`]), a [`ground::Ground`] over a terrain, a
//! [`control::Controller`], a [`sim::RoverSystem`] that joins them into an
//! ODE, and an integrator (`examples/drive.rs` in the repository).

#![warn(missing_docs)]

pub mod control;
pub mod described;
pub mod generic_plant;
pub mod ground;
pub mod quasi_static;
pub mod row;
pub mod ruts;
pub mod sim;
pub mod soil;
pub mod wheel_law;

/// The integrators (crate `rover-integrate`), re-exported so that one
/// dependency gives a whole run.
pub use rover_integrate as integrate;
/// The terrains (crate `rover-terrain`), re-exported for the same reason.
pub use rover_terrain as terrain;

pub use described::RoverDescription;
pub use generic_plant::GenericPlant;

/// What `#[derive(Rover)]`'s code names, so that a crate depending on
/// rover-runtime needs no other dependency for it; not an API.
#[doc(hidden)]
pub mod __private {
    pub use libm;
    pub use rover_dynamics;
}
