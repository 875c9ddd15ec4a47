//! The `rover` command line as a library: every subcommand is a function a
//! test can call (`rover::cli::simulate(&SimulateArgs)`).

pub mod cli;
#[cfg(feature = "drive")]
pub mod drive;
pub mod rover_source;
pub mod sweep;
