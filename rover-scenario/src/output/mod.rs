//! What a run writes: the CSV time histories, the summary, the rut map
//! and, with the `mcap` feature, the MCAP log.

mod body_box;
mod circle_fit;
pub(crate) mod csv_writer;
#[cfg(feature = "mcap")]
pub mod foxglove;
mod height_grid;
mod row_sink;
mod rut_grid;
mod slide;
mod summary;
mod write_whole;

pub use body_box::body_box;
pub use circle_fit::{Circle, fit_circle};
pub use csv_writer::CsvWriter;
pub use height_grid::{HeightGrid, PATH_MARGIN, PathBox, PathGround, VIEW_NODES};
pub use row_sink::RowSink;
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
