//! `rover check <file-or-builtin>`.

use clap::Args;

use rover_scenario::prepare::load_rover;

use crate::error::CliError;

/// Arguments of `rover check`.
#[derive(Debug, Args)]
pub struct CheckArgs {
    /// A built-in rover (exomars, swing4, mer, lrv) or a description file.
    pub rover: String,
}

/// Validate the rover and return the report `rover check` prints.
pub fn check(args: &CheckArgs) -> Result<String, CliError> {
    let spec = load_rover(&args.rover, None)?;
    Ok(rover_spec::report::check_report(&spec))
}
