//! The plot metadata checked against the data: one name per coordinate and
//! per wheel, a title, and the settling time if it falls inside the run.

use std::path::Path;

use crate::run_data::RunData;
use crate::{PlotError, PlotMeta};

/// Names and markers ready to draw.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Labels {
    /// Figure title prefix.
    pub title: String,
    /// One name per suspension coordinate.
    pub coordinate_names: Vec<String>,
    /// One flag per suspension coordinate: an angle (plotted in degrees).
    pub angular: Vec<bool>,
    /// One name per wheel.
    pub wheel_names: Vec<String>,
    /// End of settling, when it lies inside the run (after its first sample).
    pub settle: Option<f64>,
    /// Number of body outlines on the trajectories.
    pub outline_instants: usize,
}

impl Labels {
    /// Fills the defaults of `meta` and checks it against `data` (read from `path`).
    pub(crate) fn resolve(path: &Path, meta: &PlotMeta, data: &RunData) -> Result<Self, PlotError> {
        let meta_error = |message: String| PlotError::Meta {
            path: path.to_path_buf(),
            message,
        };
        let m = data.y.len();
        let n = data.wheels.len();
        let coordinate_names = if meta.coordinate_names.is_empty() {
            (1..=m).map(|k| format!("y{k}")).collect()
        } else if meta.coordinate_names.len() == m {
            meta.coordinate_names.clone()
        } else {
            return Err(meta_error(format!(
                "{} coordinate names given but the CSV has {m} suspension coordinates (y1..y{m}); \
                 give one name per coordinate, or none",
                meta.coordinate_names.len()
            )));
        };
        let angular = if meta.angular.is_empty() {
            vec![false; m]
        } else if meta.angular.len() == m {
            meta.angular.clone()
        } else {
            return Err(meta_error(format!(
                "{} angular flags given but the CSV has {m} suspension coordinates (y1..y{m}); \
                 give one flag per coordinate, or none",
                meta.angular.len()
            )));
        };
        let wheel_names = if meta.wheel_names.is_empty() {
            (1..=n).map(|j| format!("W{j}")).collect()
        } else if meta.wheel_names.len() == n {
            meta.wheel_names.clone()
        } else {
            return Err(meta_error(format!(
                "{} wheel names given but the CSV has {n} wheels (W1X..W{n}X); \
                 give one name per wheel, or none",
                meta.wheel_names.len()
            )));
        };
        if !(meta.settle_time.is_finite() && meta.settle_time >= 0.0) {
            return Err(meta_error(format!(
                "settle_time must be a finite time >= 0 s, got {}",
                meta.settle_time
            )));
        }
        let (t0, t1) = (data.t[0], data.t[data.t.len() - 1]);
        let settle = (meta.settle_time > t0 && meta.settle_time <= t1).then_some(meta.settle_time);
        let title = if meta.title.trim().is_empty() {
            path.file_stem().map_or_else(
                || "rover run".to_string(),
                |s| s.to_string_lossy().into_owned(),
            )
        } else {
            meta.title.clone()
        };
        Ok(Self {
            title,
            coordinate_names,
            angular,
            wheel_names,
            settle,
            outline_instants: meta.outline_instants,
        })
    }
}
