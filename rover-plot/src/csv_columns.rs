//! Reading columns of numbers from a CSV by name, checked: every cell
//! read a finite number, the rows whole, time not going backwards.

use std::path::Path;

use crate::PlotError;

/// Reads the CSV at `path`: `pick` gets the header's names and says which
/// columns to parse (the time column's index and every index used);
/// returns one vector per header column, those not picked left empty.
pub(crate) fn read_columns(
    path: &Path,
    pick: impl FnOnce(&[&str]) -> Result<(usize, Vec<usize>), PlotError>,
) -> Result<Vec<Vec<f64>>, PlotError> {
    let bytes =
        rover_files::read(path, rover_files::Limit::Data).map_err(|source| PlotError::Read {
            path: path.to_path_buf(),
            source,
        })?;
    let mut reader = csv::ReaderBuilder::new()
        .has_headers(true)
        .flexible(true)
        .from_reader(bytes.as_slice());
    let malformed = |e: csv::Error| {
        let line = e.position().map_or(1, csv::Position::line);
        let message = e.to_string();
        match e.into_kind() {
            csv::ErrorKind::Io(source) => PlotError::Read {
                path: path.to_path_buf(),
                source,
            },
            _ => PlotError::Malformed {
                path: path.to_path_buf(),
                line,
                message,
            },
        }
    };
    let header = reader.headers().map_err(malformed)?.clone();
    let names: Vec<&str> = header.iter().map(str::trim).collect();
    if names.iter().all(|n| n.is_empty()) {
        return Err(PlotError::NoHeader {
            path: path.to_path_buf(),
        });
    }
    let (t, used) = pick(&names)?;
    let mut columns: Vec<Vec<f64>> = vec![Vec::new(); names.len()];
    let mut record = csv::StringRecord::new();
    while reader.read_record(&mut record).map_err(malformed)? {
        let line = record.position().map_or(0, csv::Position::line);
        if record.len() != names.len() {
            return Err(PlotError::FieldCount {
                path: path.to_path_buf(),
                line,
                found: record.len(),
                expected: names.len(),
            });
        }
        for &index in &used {
            let text = record[index].trim();
            let cell = |text: &str| (names[index].to_string(), index + 1, text.to_string());
            let value: f64 = text.parse().map_err(|_| {
                let (column, index, text) = cell(text);
                PlotError::NotANumber {
                    path: path.to_path_buf(),
                    line,
                    column,
                    index,
                    text,
                }
            })?;
            if !value.is_finite() {
                let (column, index, text) = cell(text);
                return Err(PlotError::NotFinite {
                    path: path.to_path_buf(),
                    line,
                    column,
                    index,
                    text,
                });
            }
            if index == t
                && let Some(&previous) = columns[index].last()
                && value < previous
            {
                return Err(PlotError::TimeBackwards {
                    path: path.to_path_buf(),
                    line,
                    t: value,
                    previous,
                });
            }
            columns[index].push(value);
        }
    }
    if columns[t].is_empty() {
        return Err(PlotError::NoRows {
            path: path.to_path_buf(),
        });
    }
    Ok(columns)
}
