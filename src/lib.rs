//! The `rover` command line as a library: every subcommand is a function a
//! test can call (`rover::cli::simulate(&SimulateArgs)`). The work itself
//! is the library crates': a run is prepared and run by `rover-scenario`
//! (`rover_scenario::prepare`), which the Python package uses too.

pub mod cli;
#[cfg(feature = "drive")]
pub mod drive;
pub mod error;
