//! Subcommands.

mod check;
#[cfg(feature = "codegen")]
mod codegen;
mod linearize;
#[cfg(feature = "reproduce")]
mod reproduce;
mod simulate;
mod sweep;

use std::process::ExitCode;

use clap::{Parser, Subcommand};

pub use check::{CheckArgs, check};
#[cfg(feature = "codegen")]
pub use codegen::{CodegenArgs, CodegenLevel, codegen};
pub use linearize::{LinearizeArgs, linearize_cmd};
#[cfg(feature = "reproduce")]
pub use reproduce::{ReproduceArgs, calibrated, reproduce};
pub use simulate::{
    Prepared, SimulateArgs, SimulateReport, build_plant, generated_plant, simulate,
};
pub use sweep::{SweepArgs, sweep};

/// Simulate wheeled planetary rovers on rough terrain (Chen & Genta 2012).
#[derive(Debug, Parser)]
#[command(name = "rover", version, about)]
pub struct Cli {
    /// What to do.
    #[command(subcommand)]
    pub command: Command,
}

/// The subcommands.
#[derive(Debug, Subcommand)]
pub enum Command {
    /// Validate a rover and print its coordinates, bodies, fitted polynomials and rest geometry.
    Check(CheckArgs),
    /// Run a scenario: CSV time histories, plots and a summary.
    Simulate(SimulateArgs),
    /// The rover's modes on flat ground, parked, driving straight or turning steadily: frequencies, damping and shapes of its small motions.
    Linearize(LinearizeArgs),
    /// Write a rover's generated, allocation-free plant as a standalone Rust module.
    #[cfg(feature = "codegen")]
    Codegen(CodegenArgs),
    /// Run tasks of a sweep plan (one worker of a job array), or gather their records into one table.
    Sweep(SweepArgs),
    /// Rerun the paper's figures and write docs/REPRODUCTION.md.
    #[cfg(feature = "reproduce")]
    Reproduce(ReproduceArgs),
    /// Drive a rover live: the simulation paced to the wall clock, a 3D view
    /// in the browser, a WebSocket for rigs (docs/DRIVE.md).
    #[cfg(feature = "drive")]
    Drive(crate::drive::DriveArgs),
    /// Animate a finished run's run.csv in the browser.
    #[cfg(feature = "drive")]
    View(crate::drive::ViewArgs),
}

/// Errors a subcommand reports; printed once by `main`.
#[derive(Debug, thiserror::Error)]
pub enum CliError {
    /// The rover description is invalid (the rendered diagnostics).
    #[error("{0}")]
    Spec(#[from] rover_spec::SpecError),
    /// The scenario file is invalid.
    #[error("{0}")]
    Scenario(#[from] rover_scenario::scenario::ScenarioError),
    /// The run could not start: the scenario does not fit the rover.
    #[error("{}{}", location, source)]
    Setup {
        /// `file:line: ` of the offending field, when known.
        location: String,
        /// The error.
        source: rover_scenario::simulate::SetupError,
    },
    /// Something else, with its message.
    #[error("{0}")]
    Other(String),
}

impl CliError {
    /// Whether the message is already rendered as diagnostics, each headed
    /// `error:` (a description's), so that the caller adds no prefix.
    pub fn is_rendered(&self) -> bool {
        matches!(self, CliError::Spec(_))
    }

    /// The message as the command line prints it: rendered diagnostics as
    /// they are, anything else headed `error: `. The Python package raises
    /// exceptions with this same text.
    pub fn user_message(&self) -> String {
        if self.is_rendered() {
            self.to_string()
        } else {
            format!("error: {self}")
        }
    }
}

/// Print a command's text on standard output. A reader that has gone
/// away (`rover codegen swing4 | head`) ends the output quietly, as for
/// any Unix filter; any other failure is an error, never a panic.
pub(crate) fn print_stdout(text: &str) -> Result<(), CliError> {
    use std::io::Write;
    let mut out = std::io::stdout().lock();
    match out.write_all(text.as_bytes()).and_then(|()| out.flush()) {
        Err(e) if e.kind() != std::io::ErrorKind::BrokenPipe => {
            Err(CliError::Other(format!("writing to standard output: {e}")))
        }
        _ => Ok(()),
    }
}

/// Write `text` to `path` whole or not at all: into a sibling temporary
/// file first, renamed over `path` only once complete, so that a full disk
/// or an interrupted run never leaves a truncated file that looks finished.
pub fn write_whole(path: &std::path::Path, text: &str) -> Result<(), CliError> {
    let mut partial = path.as_os_str().to_owned();
    partial.push(format!(".partial-{}", std::process::id()));
    let partial = std::path::PathBuf::from(partial);
    let written = std::fs::write(&partial, text).and_then(|()| std::fs::rename(&partial, path));
    written.map_err(|e| {
        let _ = std::fs::remove_file(&partial);
        CliError::Other(format!("{}: cannot write: {e}", path.display()))
    })
}

/// Run a parsed command line; the exit code says how it went (0 success,
/// 1 a run that stopped early, 2 bad input).
pub fn run(cli: Cli) -> Result<ExitCode, CliError> {
    match cli.command {
        Command::Check(a) => {
            print_stdout(&check(&a)?)?;
            Ok(ExitCode::SUCCESS)
        }
        #[cfg(feature = "codegen")]
        Command::Codegen(a) => {
            codegen(&a)?;
            Ok(ExitCode::SUCCESS)
        }
        #[cfg(feature = "reproduce")]
        Command::Reproduce(a) => {
            let out = reproduce(&a)?;
            eprintln!("wrote {}", out.display());
            Ok(ExitCode::SUCCESS)
        }
        Command::Linearize(a) => {
            print_stdout(&linearize_cmd(&a)?)?;
            Ok(ExitCode::SUCCESS)
        }
        Command::Sweep(a) => {
            sweep(&a)?;
            Ok(ExitCode::SUCCESS)
        }
        #[cfg(feature = "drive")]
        Command::Drive(a) => {
            crate::drive::drive(&a)?;
            Ok(ExitCode::SUCCESS)
        }
        #[cfg(feature = "drive")]
        Command::View(a) => {
            crate::drive::view(&a)?;
            Ok(ExitCode::SUCCESS)
        }
        Command::Simulate(a) => {
            let report = simulate(&a)?;
            Ok(if report.summary.complete {
                ExitCode::SUCCESS
            } else {
                ExitCode::from(1)
            })
        }
    }
}
