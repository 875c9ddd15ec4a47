//! The plotted quantities of a run, read from its CSV and checked.

use std::path::Path;

use crate::PlotError;
use crate::column_layout::ColumnLayout;
use crate::csv_columns::read_columns;

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
        let mut layout = None;
        let mut columns = read_columns(path, |names| {
            let l = ColumnLayout::from_header(path, names)?;
            let used = (l.t, l.used_columns());
            layout = Some(l);
            Ok(used)
        })?;
        let layout = layout.expect("the header was read");

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
