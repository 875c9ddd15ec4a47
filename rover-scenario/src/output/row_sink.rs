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

impl<T: RowSink + ?Sized> RowSink for &mut T {
    fn start(&mut self, columns: &Columns) -> std::io::Result<()> {
        (**self).start(columns)
    }
    fn row(&mut self, values: &[f64]) -> std::io::Result<()> {
        (**self).row(values)
    }
    fn finish(&mut self, terrain: Option<&Terrain>) -> std::io::Result<()> {
        (**self).finish(terrain)
    }
}

/// No sink: nothing to do.
impl<T: RowSink> RowSink for Option<T> {
    fn start(&mut self, columns: &Columns) -> std::io::Result<()> {
        self.as_mut().map_or(Ok(()), |s| s.start(columns))
    }
    fn row(&mut self, values: &[f64]) -> std::io::Result<()> {
        self.as_mut().map_or(Ok(()), |s| s.row(values))
    }
    fn finish(&mut self, terrain: Option<&Terrain>) -> std::io::Result<()> {
        self.as_mut().map_or(Ok(()), |s| s.finish(terrain))
    }
}

/// Two sinks, each given every call in turn; the first error is returned,
/// after both have had the call (each finishes even when the other fails).
impl<A: RowSink, B: RowSink> RowSink for (A, B) {
    fn start(&mut self, columns: &Columns) -> std::io::Result<()> {
        let a = self.0.start(columns);
        a.and(self.1.start(columns))
    }
    fn row(&mut self, values: &[f64]) -> std::io::Result<()> {
        let a = self.0.row(values);
        a.and(self.1.row(values))
    }
    fn finish(&mut self, terrain: Option<&Terrain>) -> std::io::Result<()> {
        let a = self.0.finish(terrain);
        a.and(self.1.finish(terrain))
    }
}
