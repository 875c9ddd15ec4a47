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
        write_finite_row(&mut self.out, self.columns.names(), &self.row)?;
        Ok(&self.row)
    }

    /// Flush and return the sink.
    pub fn into_inner(mut self) -> std::io::Result<W> {
        self.out.flush()?;
        Ok(self.out)
    }
}

/// One line of `row`'s numbers (each in its shortest exact form), or an
/// error naming the first non-finite one by its column in `names`,
/// nothing written then.
pub(crate) fn write_finite_row<W: Write>(
    out: &mut W,
    names: &[String],
    row: &[f64],
) -> std::io::Result<()> {
    if let Some(k) = row.iter().position(|v| !v.is_finite()) {
        return Err(std::io::Error::other(format!(
            "column {} (`{}`) is {}: not written",
            k + 1,
            names[k],
            row[k]
        )));
    }
    for (k, v) in row.iter().enumerate() {
        if k > 0 {
            out.write_all(b",")?;
        }
        rover_files::write_f64(out, *v)?;
    }
    out.write_all(b"\n")
}
