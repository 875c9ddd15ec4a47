//! What a subcommand reports when it cannot do its work; printed once by
//! `main`, with the exit code that says which kind it was.

use std::path::{Path, PathBuf};

use rover_scenario::output::WriteError;
use rover_scenario::prepare::PrepareError;
use rover_scenario::scenario::ScenarioError;
use rover_scenario::sweep::SweepError;
use rover_spec::SpecError;

/// Errors a subcommand reports.
#[derive(Debug, thiserror::Error)]
pub enum CliError {
    /// The rover description is invalid (the rendered diagnostics).
    #[error("{0}")]
    Spec(#[from] SpecError),
    /// The scenario file is invalid.
    #[error("{0}")]
    Scenario(#[from] ScenarioError),
    /// The run could not be prepared or could not start (boxed: the
    /// scenario's errors are large, and every command returns this type).
    #[error("{0}")]
    Prepare(Box<PrepareError>),
    /// A sweep plan or task cannot run.
    #[error("{0}")]
    Sweep(Box<SweepError>),
    /// An output file could not be written whole.
    #[error("{0}")]
    Write(#[from] WriteError),
    /// A file or folder could not be read, created or written.
    #[error("{}: cannot {doing}: {source}", path.display())]
    Io {
        /// The file or folder.
        path: PathBuf,
        /// What was being done ("create the CSV").
        doing: &'static str,
        /// The system's reason.
        source: std::io::Error,
    },
    /// A sensor log does not fit the scenario's `[sensors]`.
    #[error("{0}")]
    SensorLog(Box<rover_scenario::sensor_log::SensorLogError>),
    /// A run's truth (its run.csv) cannot be read.
    #[error("{0}")]
    Truth(#[from] rover_scenario::truth_log::TruthError),
    /// Standard output could not be written (other than a closed pipe).
    #[error("writing to standard output: {0}")]
    Stdout(std::io::Error),
    /// Command-line arguments that do not go together or are out of range;
    /// the message names the flag and how to fix it.
    #[error("{0}")]
    Usage(String),
    /// The rover could not be linearized.
    #[error("{rover}: cannot linearize: {source}")]
    Linearize {
        /// The rover's name.
        rover: String,
        /// Why.
        source: rover_scenario::linearize::LinearizeError,
    },
    /// The run's plots could not be drawn.
    #[cfg(feature = "plots")]
    #[error("{0}")]
    Plot(#[from] rover_plot::PlotError),
    /// The code generator failed.
    #[cfg(feature = "codegen")]
    #[error("{0}")]
    Codegen(#[from] rover_codegen::CodegenError),
    /// A figure of the reproduction cannot be made, or a claim of the
    /// paper that it checks no longer holds.
    #[cfg(feature = "reproduce")]
    #[error("{0}")]
    Reproduce(String),
    /// An FMU or C library could not be exported.
    #[error("{0}")]
    Export(rover_export::ExportError),
    /// The live server or view could not start or serve.
    #[cfg(feature = "drive")]
    #[error("{0}")]
    Drive(String),
}

impl From<PrepareError> for CliError {
    fn from(e: PrepareError) -> Self {
        CliError::Prepare(Box::new(e))
    }
}

impl From<rover_export::ExportError> for CliError {
    fn from(e: rover_export::ExportError) -> Self {
        match e {
            rover_export::ExportError::Prepare(p) => CliError::Prepare(p),
            e => CliError::Export(e),
        }
    }
}

impl From<SweepError> for CliError {
    fn from(e: SweepError) -> Self {
        CliError::Sweep(Box::new(e))
    }
}

impl CliError {
    /// An I/O failure on `path` while `doing` something.
    pub fn io(path: impl Into<PathBuf>, doing: &'static str, source: std::io::Error) -> Self {
        CliError::Io {
            path: path.into(),
            doing,
            source,
        }
    }

    /// Refuse an output file `out` (given by `flag`) that is one of the
    /// command's `inputs` (which writing it would destroy) or that is not a
    /// place for a file (a folder, a device, a FIFO, a link), before any
    /// work is done.
    pub fn check_output_file(flag: &str, out: &Path, inputs: &[&Path]) -> Result<(), CliError> {
        if let Some(input) = inputs.iter().find(|i| rover_files::same_file(out, i)) {
            return Err(CliError::Usage(format!(
                "{flag} {}: is the input {}, which writing would destroy; give another path",
                out.display(),
                input.display()
            )));
        }
        match std::fs::symlink_metadata(out) {
            Ok(meta) if !meta.is_file() => {
                let what = if meta.is_dir() {
                    "a folder"
                } else if meta.file_type().is_symlink() {
                    "a symbolic link"
                } else {
                    "a device, FIFO or socket"
                };
                Err(CliError::Usage(format!(
                    "{flag} {}: is {what}; give the path of a file to write (rover writes only \
                     regular files, never through a link)",
                    out.display()
                )))
            }
            _ => Ok(()),
        }
    }

    /// Whether the message is already rendered as diagnostics, each headed
    /// `error:` (a description's), so that the caller adds no prefix.
    pub fn is_rendered(&self) -> bool {
        match self {
            CliError::Spec(_) => true,
            CliError::Prepare(e) => e.is_rendered(),
            CliError::Sweep(e) => matches!(&**e, SweepError::Run(p) if p.is_rendered()),
            _ => false,
        }
    }

    /// The message as the command line prints it: rendered diagnostics as
    /// they are, anything else headed `error: `.
    pub fn user_message(&self) -> String {
        let text = if self.is_rendered() {
            self.to_string()
        } else {
            format!("error: {self}")
        };
        printable(&text)
    }
}

/// `text` with every control character but the line break and the tab
/// escaped (`\u{1b}`): an error quotes names and tokens from files that
/// may not be the user's own, and an escape sequence in one must reach the
/// terminal as text, not as a command to it.
pub fn printable(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    for c in text.chars() {
        if c.is_control() && c != '\n' && c != '\t' {
            out.extend(c.escape_default());
        } else {
            out.push(c);
        }
    }
    out
}

/// Print a command's text on standard output. A reader that has gone
/// away (`rover codegen swing4 | head`) ends the output quietly, as for
/// any Unix filter; any other failure is an error, never a panic.
pub(crate) fn print_stdout(text: &str) -> Result<(), CliError> {
    use std::io::Write;
    let mut out = std::io::stdout().lock();
    match out.write_all(text.as_bytes()).and_then(|()| out.flush()) {
        Err(e) if e.kind() != std::io::ErrorKind::BrokenPipe => Err(CliError::Stdout(e)),
        _ => Ok(()),
    }
}
