//! What a run writes: the CSV time histories and the summary.

mod circle_fit;
mod csv_writer;
mod slide;
mod summary;
mod write_whole;

pub use circle_fit::{Circle, fit_circle};
pub use csv_writer::CsvWriter;
pub use slide::{
    AxleSlide, SLIDE_WINDOW, SLIDE_YAW_DEG, Slide, SlideTrack, SuddenSlide, axles_by_rest_x, slide,
};
pub use summary::{
    PathDeviation, RunEnd, RunLog, STALL_FRACTION, STALL_MIN_DISTANCE, STALL_WINDOW, Stall, Status,
    Summary,
};
pub use write_whole::{WriteError, write_whole};
