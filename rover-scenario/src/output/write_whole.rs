//! Files written whole or not at all.

use std::path::{Path, PathBuf};

/// A file that could not be written.
#[derive(Debug, thiserror::Error)]
#[error("{}: cannot write: {source}", path.display())]
pub struct WriteError {
    /// The file.
    pub path: PathBuf,
    /// The system's reason.
    pub source: std::io::Error,
}

/// Write `text` to `path` whole or not at all, as a regular file and never
/// through a link ([`rover_files::write_whole`]).
pub fn write_whole(path: &Path, text: &str) -> Result<(), WriteError> {
    rover_files::write_whole(path, text.as_bytes()).map_err(|source| WriteError {
        path: path.to_path_buf(),
        source,
    })
}
