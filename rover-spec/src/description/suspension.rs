//! The `[[suspension]]` tables: one struct per kind of the library
//! (MODEL.md §3), selected by `kind`.

use serde::{Deserialize, Serialize};

use super::{CoordinateDesc, FitDesc, MassDesc};

/// A suspension, tagged by `kind`.
#[allow(clippy::large_enum_variant)] // built once per suspension; boxing would burden Rust-built descriptions
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(tag = "kind", rename_all = "snake_case")]
pub enum SuspensionDesc {
    /// Trailing or leading arm on a pivot with axis e_y.
    LongitudinalSwingArm(SwingArmDesc),
    /// Swing arm on a pivot with axis e_x; the wheel cambers with it.
    TransversalSwingArm(TransversalSwingArmDesc),
    /// Double wishbone (four-bar linkage in the y–z plane).
    DoubleWishbone(DoubleWishboneDesc),
    /// Free rocker on a pivot with axis e_y carrying several wheels.
    LongitudinalRocker(RockerDesc),
    /// Free rocker on a pivot with axis e_x; its wheels camber with it.
    TransversalRocker(RockerDesc),
    /// MER-type rocker-bogie, both sides, joined by a differential.
    RockerBogie(RockerBogieDesc),
    /// Polynomials given directly (Z_ij, member axes, camber and steer).
    Polynomial(PolynomialDesc),
}

impl SuspensionDesc {
    /// The suspension's name.
    pub fn name(&self) -> &str {
        match self {
            SuspensionDesc::LongitudinalSwingArm(s) => &s.name,
            SuspensionDesc::TransversalSwingArm(s) => &s.name,
            SuspensionDesc::DoubleWishbone(s) => &s.name,
            SuspensionDesc::LongitudinalRocker(s) | SuspensionDesc::TransversalRocker(s) => &s.name,
            SuspensionDesc::RockerBogie(s) => &s.name,
            SuspensionDesc::Polynomial(s) => &s.name,
        }
    }

    /// The `kind` keyword.
    pub fn kind(&self) -> &'static str {
        match self {
            SuspensionDesc::LongitudinalSwingArm(_) => "longitudinal_swing_arm",
            SuspensionDesc::TransversalSwingArm(_) => "transversal_swing_arm",
            SuspensionDesc::DoubleWishbone(_) => "double_wishbone",
            SuspensionDesc::LongitudinalRocker(_) => "longitudinal_rocker",
            SuspensionDesc::TransversalRocker(_) => "transversal_rocker",
            SuspensionDesc::RockerBogie(_) => "rocker_bogie",
            SuspensionDesc::Polynomial(_) => "polynomial",
        }
    }

    /// The carried masses that are not wheels.
    pub fn bodies(&self) -> &[MassDesc] {
        match self {
            SuspensionDesc::LongitudinalSwingArm(s) => &s.bodies,
            SuspensionDesc::TransversalSwingArm(s) => &s.bodies,
            SuspensionDesc::DoubleWishbone(s) => &s.bodies,
            SuspensionDesc::LongitudinalRocker(s) | SuspensionDesc::TransversalRocker(s) => {
                &s.bodies
            }
            SuspensionDesc::RockerBogie(s) => &s.bodies,
            SuspensionDesc::Polynomial(s) => &s.bodies,
        }
    }

    /// The fit options, if given.
    pub fn fit(&self) -> Option<&FitDesc> {
        match self {
            SuspensionDesc::LongitudinalSwingArm(s) => s.fit.as_ref(),
            SuspensionDesc::TransversalSwingArm(s) => s.fit.as_ref(),
            SuspensionDesc::DoubleWishbone(s) => s.fit.as_ref(),
            SuspensionDesc::LongitudinalRocker(s) | SuspensionDesc::TransversalRocker(s) => {
                s.fit.as_ref()
            }
            SuspensionDesc::RockerBogie(s) => s.fit.as_ref(),
            SuspensionDesc::Polynomial(_) => None,
        }
    }
}

/// Longitudinal swing arm: `u = A + Ry(y)·[0, 0, −l]` (paper eq. 33).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SwingArmDesc {
    /// Name, unique in the rover.
    pub name: String,
    /// Pivot A, body components \[m\].
    pub pivot: [f64; 3],
    /// Arm length l from pivot to wheel centre \[m\], > 0.
    pub length: f64,
    /// The arm angle y (0 = arm hanging straight down; positive swings the
    /// wheel backwards).
    pub coordinate: CoordinateDesc,
    /// Fit options.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub fit: Option<FitDesc>,
    /// Extra carried masses (member `arm`, point `wheel`).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub bodies: Vec<MassDesc>,
}

/// Transversal swing arm: `u = A + Rx(y)·[0, 0, −l]`, camber `γ = y − y_ref`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TransversalSwingArmDesc {
    /// Name, unique in the rover.
    pub name: String,
    /// Pivot A, body components \[m\].
    pub pivot: [f64; 3],
    /// Arm length l \[m\], > 0.
    pub length: f64,
    /// Angle y_ref at which the wheel is vertical \[rad\] (default: rest).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub camber_reference: Option<f64>,
    /// Same in degrees.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub camber_reference_deg: Option<f64>,
    /// The arm angle y about e_x (0 = hanging straight down).
    pub coordinate: CoordinateDesc,
    /// Fit options.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub fit: Option<FitDesc>,
    /// Extra carried masses (member `arm`, point `wheel`).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub bodies: Vec<MassDesc>,
}

/// Double wishbone in the plane x = `x`; the coordinate is the lower arm's
/// angle about e_x (0 = horizontal, pointing outboard).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct DoubleWishboneDesc {
    /// Name, unique in the rover.
    pub name: String,
    /// Longitudinal position of the linkage's plane \[m\].
    pub x: f64,
    /// Lower arm's inner pivot (y, z) \[m\]; its sign of y is the side.
    pub lower_pivot: [f64; 2],
    /// Lower arm length, inner pivot to ball joint \[m\].
    pub lower_length: f64,
    /// Upper arm's inner pivot (y, z) \[m\].
    pub upper_pivot: [f64; 2],
    /// Upper arm length \[m\].
    pub upper_length: f64,
    /// Upright length, lower to upper ball joint \[m\].
    pub upright_length: f64,
    /// Wheel centre in the upright frame: along the upright (from the lower
    /// ball joint towards the upper) and across it (outboard) \[m\].
    pub wheel_offset: [f64; 2],
    /// Lower arm angle y about e_x.
    pub coordinate: CoordinateDesc,
    /// Fit options.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub fit: Option<FitDesc>,
    /// Extra carried masses (members `lower_arm`, `upper_arm`, `upright`;
    /// point `wheel`).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub bodies: Vec<MassDesc>,
}

/// One arm of a rocker: wheel k at `A + R(y + β_k)·[0, 0, −l_k]`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ArmDesc {
    /// The point's name (wheels refer to it).
    pub name: String,
    /// Length l_k \[m\], > 0.
    pub length: f64,
    /// β_k \[rad\].
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub angle: Option<f64>,
    /// β_k \[deg\].
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub angle_deg: Option<f64>,
}

/// A free rocker (longitudinal: axis e_y; transversal: axis e_x).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RockerDesc {
    /// Name, unique in the rover.
    pub name: String,
    /// Pivot A, body components \[m\].
    pub pivot: [f64; 3],
    /// The arms, one point each.
    pub arms: Vec<ArmDesc>,
    /// The rocker angle y (0 at rest by default).
    pub coordinate: CoordinateDesc,
    /// Fit options.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub fit: Option<FitDesc>,
    /// Extra carried masses (member `rocker`, or an arm's point).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub bodies: Vec<MassDesc>,
}

/// MER-type rocker-bogie, both sides. Positions are the left side's at rest
/// (the right side mirrors them in y). Rocker angle y_r on the left, −y_r on
/// the right (differential); bogie angles relative to the body.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RockerBogieDesc {
    /// Name, unique in the rover.
    pub name: String,
    /// Left rocker pivot (on the differential axis) \[m\].
    pub pivot: [f64; 3],
    /// Left front wheel centre at rest \[m\].
    pub front_wheel: [f64; 3],
    /// Left bogie pivot on the rocker, at rest \[m\].
    pub bogie_pivot: [f64; 3],
    /// Left middle wheel centre at rest \[m\].
    pub middle_wheel: [f64; 3],
    /// Left rear wheel centre at rest \[m\].
    pub rear_wheel: [f64; 3],
    /// Rocker angle y_r about e_y (left side).
    pub rocker: CoordinateDesc,
    /// Left bogie angle about e_y, relative to the body.
    pub bogie_left: CoordinateDesc,
    /// Right bogie angle about e_y, relative to the body.
    pub bogie_right: CoordinateDesc,
    /// Fit options.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub fit: Option<FitDesc>,
    /// Extra carried masses (members `rocker_left`, `rocker_right`,
    /// `bogie_left`, `bogie_right`, or a wheel point).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub bodies: Vec<MassDesc>,
}

/// Polynomials given directly.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PolynomialDesc {
    /// Name, unique in the rover.
    pub name: String,
    /// Its coordinates (each needs a `name`).
    pub coordinates: Vec<CoordinateDesc>,
    /// Its points.
    pub points: Vec<PolyPointDesc>,
    /// Extra carried masses (at a `point`).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub bodies: Vec<MassDesc>,
}

/// A point given by polynomials: `u = position + Σ_i Σ_p coeffs_p·ξ_i^p`,
/// ξ_i = y_i − rest_i.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PolyPointDesc {
    /// The point's name.
    pub name: String,
    /// Constant part c_j, body components \[m\].
    pub position: [f64; 3],
    /// Per-coordinate terms (the columns of Z_ij).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub terms: Vec<PolyTermDesc>,
    /// Rotations of the member carrying the point.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub member: Vec<MemberDesc>,
    /// Camber γ(y) \[rad\].
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub camber: Option<ScalarPolyDesc>,
    /// Suspension-induced steer ε(y) \[rad\].
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub toe: Option<ScalarPolyDesc>,
}

/// One coordinate's columns of Z_ij.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PolyTermDesc {
    /// The coordinate's name.
    pub coordinate: String,
    /// Columns of Z_ij: coefficient vectors of ξ⁰, ξ¹, … [m/unitᵖ].
    pub coeffs: Vec<[f64; 3]>,
}

/// A member rotation: angle about a fixed axis as a polynomial in one coordinate.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MemberDesc {
    /// The coordinate's name.
    pub coordinate: String,
    /// Axis in body components (normalised on load).
    pub axis: [f64; 3],
    /// Coefficients of ξ⁰, ξ¹, … of the angle \[rad\]; the first must be 0.
    pub angle: Vec<f64>,
}

/// A scalar polynomial (camber, steer).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ScalarPolyDesc {
    /// Constant part \[rad\] (default 0).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub constant: Option<f64>,
    /// Per-coordinate terms.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub terms: Vec<ScalarTermDesc>,
}

/// One coordinate's coefficients of a scalar polynomial.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ScalarTermDesc {
    /// The coordinate's name.
    pub coordinate: String,
    /// Coefficients of ξ⁰, ξ¹, …
    pub coeffs: Vec<f64>,
}
