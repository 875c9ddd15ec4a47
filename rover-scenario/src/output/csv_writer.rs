//! The run's CSV (DESIGN.md "Output conventions"): state columns, wheel
//! centres, then contact and control columns.

use std::io::Write;

/// The header: `t,X,Y,Z,phi,theta,psi,y1..ym,vx,vy,vz,Ox,Oy,Oz,dy1..dym`,
/// `W{j}X,W{j}Y,W{j}Z` per wheel, `H{j}X,H{j}Y,H{j}Z,Fn{j},Fd{j},Fc{j}` per
/// wheel, `tau{j}` and `delta{j}` per wheel, the spring neutrals
/// `y0_1..y0_m` (moved by the active suspension), `V_set`.
pub fn header(m: usize, wheels: usize) -> Vec<String> {
    let mut h: Vec<String> = ["t", "X", "Y", "Z", "phi", "theta", "psi"]
        .iter()
        .map(|s| s.to_string())
        .collect();
    h.extend((1..=m).map(|i| format!("y{i}")));
    h.extend(
        ["vx", "vy", "vz", "Ox", "Oy", "Oz"]
            .iter()
            .map(|s| s.to_string()),
    );
    h.extend((1..=m).map(|i| format!("dy{i}")));
    for j in 1..=wheels {
        h.extend([format!("W{j}X"), format!("W{j}Y"), format!("W{j}Z")]);
    }
    for j in 1..=wheels {
        h.extend([
            format!("H{j}X"),
            format!("H{j}Y"),
            format!("H{j}Z"),
            format!("Fn{j}"),
            format!("Fd{j}"),
            format!("Fc{j}"),
        ]);
    }
    h.extend((1..=wheels).map(|j| format!("tau{j}")));
    h.extend((1..=wheels).map(|j| format!("delta{j}")));
    h.extend((1..=m).map(|i| format!("y0_{i}")));
    h.push("V_set".into());
    h
}

/// Writes rows of numbers, refusing non-finite values: a NaN never reaches
/// the file as if it were a result.
pub struct CsvWriter<W: Write> {
    out: W,
    columns: usize,
    row: Vec<f64>,
}

impl<W: Write> CsvWriter<W> {
    /// Start a file with its header.
    pub fn new(mut out: W, header: &[String]) -> std::io::Result<Self> {
        writeln!(out, "{}", header.join(","))?;
        Ok(Self {
            out,
            columns: header.len(),
            row: Vec::with_capacity(header.len()),
        })
    }

    /// The row being built.
    pub fn row(&mut self) -> &mut Vec<f64> {
        self.row.clear();
        &mut self.row
    }

    /// Write the row built with [`CsvWriter::row`].
    pub fn finish_row(&mut self) -> std::io::Result<()> {
        if self.row.len() != self.columns {
            return Err(std::io::Error::other(format!(
                "row has {} values for {} columns",
                self.row.len(),
                self.columns
            )));
        }
        if let Some(k) = self.row.iter().position(|v| !v.is_finite()) {
            return Err(std::io::Error::other(format!(
                "column {} is {}: not written",
                k + 1,
                self.row[k]
            )));
        }
        for (k, v) in self.row.iter().enumerate() {
            if k > 0 {
                self.out.write_all(b",")?;
            }
            write!(self.out, "{v}")?;
        }
        self.out.write_all(b"\n")
    }

    /// Flush and return the sink.
    pub fn into_inner(mut self) -> std::io::Result<W> {
        self.out.flush()?;
        Ok(self.out)
    }
}
