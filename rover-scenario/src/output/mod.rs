//! What a run writes: the CSV time histories and the summary.

mod circle_fit;
mod csv_writer;
mod summary;

pub use circle_fit::{Circle, fit_circle};
pub use csv_writer::{CsvWriter, header};
pub use summary::{
    PathDeviation, RunEnd, RunLog, STALL_FRACTION, STALL_MIN_DISTANCE, STALL_WINDOW, Stall, Status,
    Summary,
};
