//! Another sink of a run's rows besides run.csv (the MCAP log): the run's
//! loop computes each row once ([`rover_runtime::row`]), writes it to the
//! CSV, and hands the same values to the sink.

use rover_runtime::row::Columns;
use rover_terrain::Terrain;

/// What receives a run's rows besides the CSV.
pub trait RowSink {
    /// Before the first row: the rows' columns.
    fn start(&mut self, columns: &Columns) -> std::io::Result<()>;
    /// One row, in the columns' order (`values[0]` is `t`), each value
    /// finite (the CSV writer refused the row otherwise).
    fn row(&mut self, values: &[f64]) -> std::io::Result<()>;
    /// After the last row, also after a failure (the rows up to it stand):
    /// the ground the run drove on (`None` in free flight).
    fn finish(&mut self, terrain: Option<&Terrain>) -> std::io::Result<()>;
}
