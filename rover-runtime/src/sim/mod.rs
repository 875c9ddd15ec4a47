//! The simulation: the rover as an ODE system, and the driver that advances
//! it through output instants, controller samples and stop conditions.

mod error;
mod profile;
mod run;
mod system;

pub use error::{CommandError, RunError, SimError};
pub use profile::{Profile, RhsProfile};
pub use run::{OutputRow, RunOptions, RunOutcome, Stop, run};
pub use system::RoverSystem;
