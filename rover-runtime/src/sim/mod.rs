//! The simulation: the rover as an ODE system, and the driver that advances
//! it through output instants, controller samples and stop conditions.

mod error;
mod run;
mod system;

pub use error::{CommandError, RunError, SimError};
pub use run::{OutputRow, RunOptions, RunOutcome, Stop, run};
pub use system::RoverSystem;
