//! Why an export could not be written.

use std::path::{Path, PathBuf};

use rover_scenario::prepare::PrepareError;

/// An export that could not be written; the message names the file or
/// flag and how to fix it.
#[derive(Debug, thiserror::Error)]
pub enum ExportError {
    /// The rover or the scenario cannot run (boxed: the scenario's errors
    /// are large).
    #[error("{}", .0.user_message().trim_start_matches("error: "))]
    Prepare(Box<PrepareError>),
    /// A file or folder could not be read, created or written.
    #[error("{}: cannot {doing}: {source}", path.display())]
    Io {
        /// The file or folder.
        path: PathBuf,
        /// What was being done.
        doing: &'static str,
        /// The system's reason.
        source: std::io::Error,
    },
    /// The prebuilt plant library was not found.
    #[error("{0}")]
    Library(String),
    /// Arguments that do not go together or are out of range.
    #[error("{0}")]
    Usage(String),
}

impl ExportError {
    /// An I/O error on `path`.
    pub fn io(path: &Path, doing: &'static str, source: std::io::Error) -> Self {
        ExportError::Io {
            path: path.to_path_buf(),
            doing,
            source,
        }
    }
}
