//! The `fit` table of a suspension.

use serde::{Deserialize, Serialize};

/// How a suspension's exact kinematics become polynomials.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FitDesc {
    /// `taylor` or `least_squares` (default `least_squares`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub method: Option<FitMethodDesc>,
    /// Number of terms k, 2 … 12 (default 5).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub terms: Option<usize>,
    /// Largest accepted position error over the travel \[m\] (default 1e-3).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub tolerance: Option<f64>,
    /// Largest accepted error of member, camber and steer angles \[rad\]
    /// (default 1e-3).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub angle_tolerance: Option<f64>,
}

/// Fit method keyword.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum FitMethodDesc {
    /// Taylor series about the rest value.
    Taylor,
    /// Least squares over the travel range.
    LeastSquares,
}
