//! The validated rover: the numeric model and what `rover check` reports.

use rover_dynamics::Model;

use crate::description::Description;
use crate::linkage::{FitOptions, ShareError};
use crate::sketch::Sketch;

/// A validated rover description.
#[derive(Clone, Debug, PartialEq)]
pub struct Spec {
    /// The rover's name.
    pub name: String,
    /// The numeric model the equations read.
    pub model: Model,
    /// Names of y_1 … y_m.
    pub coordinate_names: Vec<String>,
    /// Whether each coordinate is a length \[m\] (else an angle \[rad\]).
    pub coordinate_linear: Vec<bool>,
    /// Names of the carried bodies j (wheels first, in wheel order).
    pub body_names: Vec<String>,
    /// Names of the wheels.
    pub wheel_names: Vec<String>,
    /// The suspensions, in order.
    pub suspensions: Vec<SuspensionInfo>,
    /// How each carried body's polynomials were obtained, index j.
    pub fits: Vec<BodyFit>,
    /// Wheel centres at rest u_j(y_c), body components \[m\], wheel order.
    pub rest_wheel_centres: Vec<[f64; 3]>,
    /// The members of the library suspensions as joints and links, for
    /// drawing the rover (empty for raw polynomial suspensions).
    pub sketch: Sketch,
    /// The description it came from.
    pub description: Description,
}

/// One suspension of a validated rover.
#[derive(Clone, Debug, PartialEq)]
pub struct SuspensionInfo {
    /// Its name.
    pub name: String,
    /// Its `kind` keyword.
    pub kind: &'static str,
    /// Its coordinates (global indices).
    pub coordinates: Vec<usize>,
    /// The fit used (`None` for raw polynomials).
    pub fit: Option<FitOptions>,
}

/// How the polynomials of one carried body were obtained.
#[derive(Clone, Debug, PartialEq)]
pub struct BodyFit {
    /// The suspension (index into [`Spec::suspensions`]).
    pub suspension: usize,
    /// The point or member it sits on.
    pub at: String,
    /// Per coordinate: the fit's maximum errors and where.
    pub shares: Vec<ShareError>,
    /// Bound on the position error over the travel box \[m\].
    pub max_position_error: f64,
    /// Bound on the angle errors \[rad\].
    pub max_angle_error: f64,
}
