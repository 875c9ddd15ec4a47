//! Reading and writing whole terrain files.

use std::path::Path;

use super::error::{FileError, Place, TerrainError};

/// The bytes of a terrain file.
pub(crate) fn read_bytes(path: &Path) -> Result<Vec<u8>, TerrainError> {
    rover_files::read(path, rover_files::Limit::Data).map_err(|source| TerrainError::Read {
        path: path.to_path_buf(),
        source,
    })
}

/// A text terrain file as UTF-8.
pub(crate) fn read_text(path: &Path) -> Result<String, TerrainError> {
    let bytes = read_bytes(path)?;
    String::from_utf8(bytes).map_err(|e| {
        let at = e.utf8_error().valid_up_to();
        let bytes = e.as_bytes();
        let line = 1 + bytes.get(..at).map_or(0, |b| b.iter().filter(|&&c| c == b'\n').count());
        FileError::at(
            path,
            Place::Line(line),
            format!("byte {at} is not valid UTF-8 text"),
            "this format is plain text; is it a binary file (PNG, TIFF) with the wrong format or extension?",
        )
    })
}

/// Writes a terrain file.
pub(crate) fn write_bytes(path: &Path, bytes: &[u8]) -> Result<(), TerrainError> {
    rover_files::write_whole(path, bytes).map_err(|source| TerrainError::Write {
        path: path.to_path_buf(),
        source,
    })
}
