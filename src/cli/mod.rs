//! Subcommands.

mod check;
#[cfg(feature = "codegen")]
mod codegen;
mod estimate;
mod export;
mod linearize;
#[cfg(feature = "reproduce")]
mod reproduce;
mod simulate;
mod sweep;
mod wheel_test;

use std::process::ExitCode;

use clap::{Parser, Subcommand};

use crate::error::{CliError, print_stdout};

pub use check::{CheckArgs, check};
#[cfg(feature = "codegen")]
pub use codegen::{CodegenArgs, CodegenLevel, codegen};
pub use estimate::{EstimateArgs, estimate};
pub use export::{CArgs, ExportArgs, ExportKind, FmiArg, FmuArgs, InputsArg, export};
pub use linearize::{LinearizeArgs, linearize_cmd};
#[cfg(feature = "reproduce")]
pub use reproduce::{ReproduceArgs, calibrated, reproduce, steer};
pub use simulate::{SimulateArgs, SimulateReport, simulate};
pub use sweep::{SweepArgs, sweep};
pub use wheel_test::{WheelTestArgs, wheel_test_cmd};

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
    /// Estimate a run's state from its sensor log with the rover's own model (an extended Kalman filter) and with dead reckoning, against the truth when known (docs/ESTIMATE.md).
    Estimate(EstimateArgs),
    /// Export a rover's plant for other tools: an FMI 3.0 or 2.0 Co-Simulation FMU, or a C library (docs/EXPORT.md).
    Export(ExportArgs),
    /// The rover's modes on flat ground, parked, driving straight or turning steadily: frequencies, damping and shapes of its small motions.
    Linearize(LinearizeArgs),
    /// Write a rover's generated, allocation-free plant as a standalone Rust module.
    #[cfg(feature = "codegen")]
    Codegen(CodegenArgs),
    /// Run tasks of a sweep plan (one worker of a job array), or gather their records into one table.
    Sweep(SweepArgs),
    /// A rigid wheel on soft soil at a load and a list of slips: sinkage, drawbar pull and torque as CSV (the single-wheel testbed).
    WheelTest(WheelTestArgs),
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
        Command::Estimate(a) => {
            let (summary, files) = estimate(&a)?;
            print_stdout(&estimate::report(&summary, &files))?;
            Ok(if summary.error.is_none() {
                ExitCode::SUCCESS
            } else {
                ExitCode::from(1)
            })
        }
        Command::Export(a) => {
            let written = export(&a)?;
            print_stdout(&export::report(&written))?;
            Ok(ExitCode::SUCCESS)
        }
        Command::Sweep(a) => {
            sweep(&a)?;
            Ok(ExitCode::SUCCESS)
        }
        Command::WheelTest(a) => {
            wheel_test::run(&a)?;
            Ok(ExitCode::SUCCESS)
        }
        #[cfg(feature = "drive")]
        Command::Drive(a) => {
            if let Some(report) = crate::drive::drive(&a)? {
                print_stdout(&report)?;
            }
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
