//! The simulation: the rover as an ODE system, the driver that advances
//! it through output instants, controller samples and stop conditions, and
//! the whole run built on the driver.

mod driver;
mod error;
mod profile;
mod run;
mod system;

pub use driver::{Driver, RunOptions};
pub use error::{CommandError, EMBEDDED_SINKAGE, EMBEDDED_SLIP, EMBEDDED_TIME, RunError, SimError};
pub use profile::{Profile, RhsProfile};
pub use run::{OutputRow, RunOutcome, Stop, run, run_with_sensors};
pub use system::{ErrorScale, RoverSystem};
