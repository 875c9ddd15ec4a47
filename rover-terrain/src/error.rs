//! Errors from building, loading and writing terrains.

use std::fmt;
use std::path::PathBuf;

/// Everything that can go wrong building a terrain, loading or writing a file.
///
/// Every message says where (file and line, cell or tag; or the parameter),
/// what is wrong, and — after `= help:` — how to fix it.
#[derive(Debug, thiserror::Error)]
pub enum TerrainError {
    /// A terrain file is corrupt or inconsistent.
    #[error("{0}")]
    File(FileError),
    /// A terrain parameter (from the scenario or from code) is out of range.
    #[error("terrain.{name}: {problem}\n  = help: {help}")]
    Parameter {
        /// The parameter's name in the `[terrain]` table, e.g. `width`.
        name: String,
        /// What is wrong, with the offending value.
        problem: String,
        /// How to fix it.
        help: String,
    },
    /// A terrain query left the map (while sampling statistics, say).
    #[error("{0}")]
    OffMap(#[from] super::height_field::OffMap),
    /// A terrain file could not be opened or read.
    #[error(
        "{}: cannot read the terrain file: {source}\n  = help: check the path \
         (a relative path is resolved from the scenario file's directory)",
        path.display()
    )]
    Read {
        /// The file.
        path: PathBuf,
        /// The operating system's reason.
        source: std::io::Error,
    },
    /// A terrain file could not be written.
    #[error(
        "{}: cannot write the terrain file: {source}\n  = help: check that the \
         directory exists and is writable",
        path.display()
    )]
    Write {
        /// The file.
        path: PathBuf,
        /// The operating system's (or encoder's) reason.
        source: std::io::Error,
    },
}

impl TerrainError {
    /// A parameter error (`terrain.<name>: <problem>`, then the help line).
    pub fn parameter(
        name: impl Into<String>,
        problem: impl Into<String>,
        help: impl Into<String>,
    ) -> TerrainError {
        TerrainError::Parameter {
            name: name.into(),
            problem: problem.into(),
            help: help.into(),
        }
    }
}

/// Where in a file a problem was found.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Place {
    /// The file as a whole (size, signature, image type).
    Whole,
    /// A 1-based line of a text file.
    Line(usize),
    /// A TIFF tag, by name and number.
    Tag(&'static str, u16),
    /// A pixel of an image, 1-based, row 1 at the top (north).
    Pixel {
        /// Image row, from the top.
        row: usize,
        /// Image column, from the left.
        column: usize,
    },
}

/// A located problem in a terrain file.
#[derive(Debug)]
pub struct FileError {
    /// The file.
    pub path: PathBuf,
    /// Where in the file.
    pub place: Place,
    /// What is wrong.
    pub problem: String,
    /// How to fix it.
    pub help: String,
}

impl FileError {
    /// A located file error, wrapped as a [`TerrainError`].
    pub fn at(
        path: impl Into<PathBuf>,
        place: Place,
        problem: impl Into<String>,
        help: impl Into<String>,
    ) -> TerrainError {
        TerrainError::File(FileError {
            path: path.into(),
            place,
            problem: problem.into(),
            help: help.into(),
        })
    }
}

impl fmt::Display for FileError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let path = self.path.display();
        match &self.place {
            Place::Whole => write!(f, "{path}: ")?,
            Place::Line(line) => write!(f, "{path}:{line}: ")?,
            Place::Tag(name, number) => write!(f, "{path}: tag {name} ({number}): ")?,
            Place::Pixel { row, column } => {
                write!(f, "{path}: pixel (row {row}, column {column}): ")?
            }
        }
        write!(f, "{}\n  = help: {}", self.problem, self.help)
    }
}

impl std::error::Error for FileError {}
