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

impl Spec {
    /// Whether the configuration `y` (one value per suspension coordinate)
    /// lies inside every coordinate's travel; if not, a sentence naming the
    /// first coordinate outside, its suspension, its value and its travel
    /// (degrees for angles, metres for lengths), `at` saying what `y` is
    /// (`"at the static equilibrium on flat ground"`, say).
    pub fn outside_travel(&self, y: &[f64], at: &str) -> Option<String> {
        let coords = &self.model.coordinates;
        let (i, (c, &v)) = coords
            .iter()
            .zip(y)
            .enumerate()
            .find(|(_, (c, v))| !(**v >= c.min && **v <= c.max))?;
        let linear = self.coordinate_linear.get(i).copied().unwrap_or(false);
        let value = |v: f64| crate::checks::coord_value(v, linear);
        let suspension = self
            .suspensions
            .iter()
            .find(|s| s.coordinates.contains(&i))
            .map_or(String::new(), |s| {
                format!(" of suspension `{}` ({})", s.name, s.kind)
            });
        Some(format!(
            "coordinate y{} `{}`{suspension} is at {} {at}, outside its travel [{}, {}]",
            i + 1,
            self.coordinate_names.get(i).map_or("", String::as_str),
            value(v),
            value(c.min),
            value(c.max)
        ))
    }
}
