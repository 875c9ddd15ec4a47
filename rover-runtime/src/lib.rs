//! The rover runtime: everything around the plant — the generic plant,
//! terrain, contact, wheel laws, control, integrators, the simulation
//! driver and its outputs.
#![warn(missing_docs)]

pub mod contact;
pub mod control;
pub mod generic_plant;
pub mod ground;
pub mod integrate;
pub mod linearize;
pub mod output;
pub mod quasi_static;
pub mod scenario;
pub mod sim;
pub mod simulate;
pub mod terrain;
pub mod wheel_law;

pub use generic_plant::GenericPlant;
