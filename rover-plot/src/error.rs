//! The one error type of the crate: every message names the file, the line
//! or column, what is wrong and what to do about it.

use std::path::PathBuf;

/// Why a run could not be plotted.
#[derive(Debug, thiserror::Error)]
pub enum PlotError {
    /// The run CSV could not be opened or read.
    #[error(
        "cannot read run CSV {}: {source}; check the path and that the run wrote its CSV",
        path.display()
    )]
    Read {
        /// The CSV file.
        path: PathBuf,
        /// What the operating system said.
        source: std::io::Error,
    },
    /// The CSV is not well-formed (bad quoting, invalid UTF-8, …).
    #[error("{}:{line}: not a valid CSV line: {message}; fix or delete line {line}", path.display())]
    Malformed {
        /// The CSV file.
        path: PathBuf,
        /// 1-based line number.
        line: u64,
        /// What the CSV reader said.
        message: String,
    },
    /// The file is empty: not even a header row.
    #[error(
        "{}: empty file, no header row; a run CSV starts with a header `t,X,Y,Z,...` \
         (write it with `rover simulate`)",
        path.display()
    )]
    NoHeader {
        /// The CSV file.
        path: PathBuf,
    },
    /// A column the plots need is not in the header.
    #[error(
        "{}:1: no column `{column}` in the header (needed for {needed_for}); \
         write the CSV with `rover simulate` or add the column",
        path.display()
    )]
    MissingColumn {
        /// The CSV file.
        path: PathBuf,
        /// The missing column's name.
        column: String,
        /// Which plot needs it.
        needed_for: &'static str,
    },
    /// A column name appears twice in the header.
    #[error(
        "{}:1: column `{column}` appears twice (columns {first} and {second}); \
         rename or remove one of them",
        path.display()
    )]
    DuplicateColumn {
        /// The CSV file.
        path: PathBuf,
        /// The repeated name.
        column: String,
        /// 1-based position of its first occurrence.
        first: usize,
        /// 1-based position of its second occurrence.
        second: usize,
    },
    /// A data line has a different number of fields than the header.
    #[error(
        "{}:{line}: {found} fields, the header has {expected}; the line is incomplete \
         or has extra fields (a run killed while writing?): fix or delete line {line}",
        path.display()
    )]
    FieldCount {
        /// The CSV file.
        path: PathBuf,
        /// 1-based line number.
        line: u64,
        /// Fields on that line.
        found: usize,
        /// Fields in the header.
        expected: usize,
    },
    /// A cell that must hold a number does not.
    #[error(
        "{}:{line}: column `{column}` (column {index}): `{text}` is not a number; \
         fix or delete line {line}",
        path.display()
    )]
    NotANumber {
        /// The CSV file.
        path: PathBuf,
        /// 1-based line number.
        line: u64,
        /// The column's name.
        column: String,
        /// 1-based column position.
        index: usize,
        /// The cell as written.
        text: String,
    },
    /// A cell holds NaN or an infinity.
    #[error(
        "{}:{line}: column `{column}` (column {index}) is `{text}`, not a finite number; \
         the run diverged there: delete line {line} and the lines after it to plot what came before",
        path.display()
    )]
    NotFinite {
        /// The CSV file.
        path: PathBuf,
        /// 1-based line number.
        line: u64,
        /// The column's name.
        column: String,
        /// 1-based column position.
        index: usize,
        /// The cell as written.
        text: String,
    },
    /// Time goes backwards from one line to the next.
    #[error(
        "{}:{line}: t = {t} is before the previous line's t = {previous}; t must not decrease \
         (are two runs appended in one file?)",
        path.display()
    )]
    TimeBackwards {
        /// The CSV file.
        path: PathBuf,
        /// 1-based line number.
        line: u64,
        /// Time on that line, s.
        t: f64,
        /// Time on the line before, s.
        previous: f64,
    },
    /// The header is there but no data line follows.
    #[error(
        "{}: header only, no data rows; the run stopped before its first output sample: \
         rerun it and check its error message",
        path.display()
    )]
    NoRows {
        /// The CSV file.
        path: PathBuf,
    },
    /// The plot metadata does not fit the CSV.
    #[error("plot metadata for {}: {message}", path.display())]
    Meta {
        /// The CSV file the metadata was given for.
        path: PathBuf,
        /// What does not fit, and how to fix it.
        message: String,
    },
    /// An output file could not be written.
    #[error(
        "cannot write plot {}: {source}; check that the output directory is writable",
        path.display()
    )]
    Write {
        /// The file or directory being written.
        path: PathBuf,
        /// What the operating system said.
        source: std::io::Error,
    },
    /// The plotting library failed while drawing (a bug here, not in the input).
    #[error("drawing `{figure}` failed: {message}; please report this with the CSV")]
    Draw {
        /// The figure's file stem.
        figure: &'static str,
        /// What the plotting library said.
        message: String,
    },
}
