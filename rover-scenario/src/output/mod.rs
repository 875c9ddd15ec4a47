//! What a run writes: the CSV time histories, the summary and the rut map.

mod circle_fit;
pub(crate) mod csv_writer;
mod rut_grid;
mod slide;
mod summary;
mod write_whole;

pub use circle_fit::{Circle, fit_circle};
pub use csv_writer::CsvWriter;
pub use rut_grid::{MAX_RUT_NODES, RUT_FILES, RUT_PNG_SCALE, RutGrid, RutGridInfo, RutSummary};
pub use slide::{
    AxleSlide, SLIDE_WINDOW, SLIDE_YAW_DEG, Slide, SlideTrack, SuddenSlide, axles_by_rest_x, slide,
};
pub use summary::{
    PathDeviation, RUNAWAY_SPEED_FACTOR, RUNAWAY_SPEED_FLOOR, RUNAWAY_WINDOW, RUNAWAY_YAW_FACTOR,
    RUNAWAY_YAW_RATE_DEG_S, RunEnd, RunLog, Runaway, STALL_FRACTION, STALL_MIN_DISTANCE,
    STALL_WINDOW, Stall, Status, Summary, plant_label,
};
pub use write_whole::{WriteError, write_whole};
