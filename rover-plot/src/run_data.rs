//! The plotted quantities of a run, read from its CSV and checked.

use std::path::Path;

use crate::PlotError;
use crate::column_layout::ColumnLayout;

/// One wheel's time histories (SI units, inertial frame).
#[derive(Debug, Clone, Default, PartialEq)]
pub(crate) struct WheelHistory {
    /// Wheel centre `W{j}X, W{j}Y, W{j}Z`, m.
    pub centre: [Vec<f64>; 3],
    /// Contact point `H{j}X, H{j}Y, H{j}Z`, m (the centre when airborne).
    pub contact: [Vec<f64>; 3],
    /// Normal force `Fn{j}`, N.
    pub normal_force: Vec<f64>,
    /// Motor torque `tau{j}`, N·m.
    pub torque: Vec<f64>,
}

/// Everything the plots draw, one value per CSV row; every value finite and
/// `t` non-decreasing.
#[derive(Debug, Clone, Default, PartialEq)]
pub(crate) struct RunData {
    /// Time, s.
    pub t: Vec<f64>,
    /// Position of G, `X, Y, Z`, m.
    pub g: [Vec<f64>; 3],
    /// Roll, pitch, yaw `phi, theta, psi`, rad.
    pub attitude: [Vec<f64>; 3],
    /// Suspension coordinates `y1..ym` (rad or m), one vector per coordinate.
    pub y: Vec<Vec<f64>>,
    /// Forward speed of the body `vx`, m/s.
    pub vx: Vec<f64>,
    /// Speed set-point `V_set`, m/s.
    pub v_set: Vec<f64>,
    /// One entry per wheel.
    pub wheels: Vec<WheelHistory>,
}

impl RunData {
    /// Reads the plotted columns of a run CSV (header row, then one row per
    /// output sample), finding them by name.
    ///
    /// Only the columns the plots use are parsed; others may hold anything.
    /// Errors name the file, the line and column, and what to do.
    pub(crate) fn from_csv(path: &Path) -> Result<Self, PlotError> {
        let bytes = rover_files::read(path, rover_files::Limit::Data).map_err(|source| {
            PlotError::Read {
                path: path.to_path_buf(),
                source,
            }
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
        let layout = ColumnLayout::from_header(path, &names)?;
        let used = layout.used_columns();

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
                if index == layout.t
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
        if columns[layout.t].is_empty() {
            return Err(PlotError::NoRows {
                path: path.to_path_buf(),
            });
        }

        let take = |columns: &mut [Vec<f64>], index: usize| std::mem::take(&mut columns[index]);
        let three = |columns: &mut [Vec<f64>], c: [usize; 3]| {
            [
                take(columns, c[0]),
                take(columns, c[1]),
                take(columns, c[2]),
            ]
        };
        let data = Self {
            t: take(&mut columns, layout.t),
            g: three(&mut columns, layout.g),
            attitude: three(&mut columns, layout.attitude),
            y: layout.y.iter().map(|&c| take(&mut columns, c)).collect(),
            vx: take(&mut columns, layout.vx),
            v_set: take(&mut columns, layout.v_set),
            wheels: layout
                .wheels
                .iter()
                .map(|w| WheelHistory {
                    centre: three(&mut columns, w.centre),
                    contact: three(&mut columns, w.contact),
                    normal_force: take(&mut columns, w.normal_force),
                    torque: take(&mut columns, w.torque),
                })
                .collect(),
        };
        Ok(data)
    }

    /// Number of rows (output samples).
    pub(crate) fn len(&self) -> usize {
        self.t.len()
    }
}
