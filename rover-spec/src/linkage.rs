//! The contract between the suspension library and the rest of the spec:
//! a suspension kind gives its exact kinematics ([`Linkage`]); [`crate::fit`]
//! turns them into the polynomials of the numeric model (MODEL.md §3).

use rover_dynamics::model::MemberRotation;
use rover_dynamics::poly::{PolyVec, ScalarPoly};

/// The range of one suspension coordinate: where the fit must hold.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CoordRange {
    /// Rest value y_c: the expansion centre, and the Taylor point.
    pub rest: f64,
    /// Lower travel limit.
    pub min: f64,
    /// Upper travel limit.
    pub max: f64,
}

/// How exact kinematics become polynomials.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FitMethod {
    /// Taylor series about the rest value (the paper's eq. 33).
    Taylor,
    /// Least squares over the travel range (better over a wide range).
    LeastSquares,
}

/// Fit options of one suspension (the description's `fit` table).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FitOptions {
    /// Taylor or least squares.
    pub method: FitMethod,
    /// Number of terms k per coordinate (powers ξ⁰ … ξ^(k−1)); default 5.
    pub terms: usize,
    /// Largest accepted position error over the range [m].
    pub tolerance: f64,
}

/// A body carried by a suspension, as fitted polynomials in the global
/// coordinates, with the fit's maximum errors over the declared range.
#[derive(Clone, Debug, PartialEq)]
pub struct FittedPoint {
    /// u_j(y), body components [m].
    pub position: PolyVec,
    /// The member's rotations (one per coordinate it turns with).
    pub member: Vec<MemberRotation>,
    /// Camber γ(y) [rad] (zero for the longitudinal kinds).
    pub camber: ScalarPoly,
    /// Suspension-induced steer ε(y) [rad].
    pub toe: ScalarPoly,
    /// Largest |u_fit − u_exact| over the range [m].
    pub max_position_error: f64,
    /// Largest |angle_fit − angle_exact| over the range, for camber, toe and
    /// member angle [rad].
    pub max_angle_error: f64,
}
