//! The run's CSV: a header naming the row's columns
//! ([`rover_runtime::row`]), then one line of numbers per output instant.

use std::io::Write;

use rover_runtime::row::{Columns, RowInputs};

/// Writes rows of numbers, refusing non-finite values: a NaN never reaches
/// the file as if it were a result.
pub struct CsvWriter<'c, W: Write> {
    out: W,
    columns: &'c Columns,
    row: Vec<f64>,
}

impl<'c, W: Write> CsvWriter<'c, W> {
    /// Start a file of `columns` with its header.
    pub fn new(mut out: W, columns: &'c Columns) -> std::io::Result<Self> {
        writeln!(out, "{}", columns.names().join(","))?;
        Ok(Self {
            out,
            row: vec![0.0; columns.len()],
            columns,
        })
    }

    /// Compute the row of `inputs` and write it; the row's values.
    pub fn write(&mut self, inputs: &RowInputs<'_>) -> std::io::Result<&[f64]> {
        self.columns.fill(inputs, &mut self.row);
        if let Some(k) = self.row.iter().position(|v| !v.is_finite()) {
            return Err(std::io::Error::other(format!(
                "column {} (`{}`) is {}: not written",
                k + 1,
                self.columns.names()[k],
                self.row[k]
            )));
        }
        for (k, v) in self.row.iter().enumerate() {
            if k > 0 {
                self.out.write_all(b",")?;
            }
            write!(self.out, "{v}")?;
        }
        self.out.write_all(b"\n")?;
        Ok(&self.row)
    }

    /// Flush and return the sink.
    pub fn into_inner(mut self) -> std::io::Result<W> {
        self.out.flush()?;
        Ok(self.out)
    }
}
