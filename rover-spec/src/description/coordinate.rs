//! One suspension coordinate: rest value, spring, damper, travel, bump stops.

use serde::{Deserialize, Serialize};

/// A suspension coordinate y_i. Angles in radians, or in degrees in the
/// `*_deg` twin of a field (give one of the two).
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CoordinateDesc {
    /// Name (default: derived from the suspension's name).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub name: Option<String>,
    /// A linear coordinate \[m\] instead of an angle (raw polynomial suspensions only).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub linear: Option<bool>,
    /// Rest value y_c [rad or m] (default 0): the initial value and the
    /// centre of the polynomial expansions.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub rest: Option<f64>,
    /// Rest value \[deg\].
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub rest_deg: Option<f64>,
    /// Spring neutral value y_0 [rad or m] (default: the rest value).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub neutral: Option<f64>,
    /// Spring neutral value \[deg\].
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub neutral_deg: Option<f64>,
    /// Lower travel limit [rad or m] (required, here or as `min_deg`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub min: Option<f64>,
    /// Lower travel limit \[deg\].
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub min_deg: Option<f64>,
    /// Upper travel limit [rad or m].
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub max: Option<f64>,
    /// Upper travel limit \[deg\].
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub max_deg: Option<f64>,
    /// Linear spring stiffness k [N·m/rad or N/m], ≥ 0 (no spring if absent).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub stiffness: Option<f64>,
    /// A nonlinear spring given as a table (instead of `stiffness`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub spring_table: Option<SpringTableDesc>,
    /// Linear damping c [N·m·s/rad or N·s/m], ≥ 0 (default 0).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub damping: Option<f64>,
    /// Bump-stop stiffness beyond the travel limits (default: 100·k, or 100
    /// N·m/rad (100 N/m) for a coordinate without spring).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub stop_stiffness: Option<f64>,
    /// Bump-stop damping (default: critical for the coordinate's effective
    /// inertia at rest).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub stop_damping: Option<f64>,
}

/// A nonlinear spring: restoring generalized force against the deflection
/// `y − y_0`, interpolated linearly, extended with the end slopes.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SpringTableDesc {
    /// Deflections [rad or m], strictly increasing, through 0.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub deflection: Option<Vec<f64>>,
    /// Deflections \[deg\].
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub deflection_deg: Option<Vec<f64>>,
    /// Force at each deflection [N·m or N]; positive pushes y up; 0 at 0.
    pub force: Vec<f64>,
}
