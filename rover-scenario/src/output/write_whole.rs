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

/// Write `text` to `path` whole or not at all: into a sibling temporary
/// file first, renamed over `path` only once complete, so that a full disk
/// or an interrupted run never leaves a truncated file that looks finished.
pub fn write_whole(path: &Path, text: &str) -> Result<(), WriteError> {
    let mut partial = path.as_os_str().to_owned();
    partial.push(format!(".partial-{}", std::process::id()));
    let partial = PathBuf::from(partial);
    let written = std::fs::write(&partial, text).and_then(|()| std::fs::rename(&partial, path));
    written.map_err(|source| {
        let _ = std::fs::remove_file(&partial);
        WriteError {
            path: path.to_path_buf(),
            source,
        }
    })
}
