//! The scalar the exact suspension kinematics are written over: `f64` for
//! values, [`crate::jet::Jet`] for exact Taylor coefficients.
//!
//! It is narrower than `rover_dynamics::Scalar`, which the equations of
//! motion are written over: the fits expand the linkages in Taylor series,
//! and a series has no `abs`, `max`, `min` or `copysign` (the contact and
//! the bump stops need them), so the linkages ask only for the smooth
//! functions a series can carry.

use std::ops::{Add, Div, Mul, Neg, Sub};

/// A real number with the functions the linkages need.
pub trait Real:
    Copy
    + Add<Output = Self>
    + Sub<Output = Self>
    + Mul<Output = Self>
    + Div<Output = Self>
    + Neg<Output = Self>
{
    /// A constant.
    fn cst(v: f64) -> Self;
    /// The value (the series' constant term).
    fn value(self) -> f64;
    /// Sine.
    fn sin(self) -> Self;
    /// Cosine.
    fn cos(self) -> Self;
    /// Square root.
    fn sqrt(self) -> Self;
    /// `atan2(self, x)`.
    fn atan2(self, x: Self) -> Self;
}

impl Real for f64 {
    fn cst(v: f64) -> Self {
        v
    }
    fn value(self) -> f64 {
        self
    }
    fn sin(self) -> Self {
        f64::sin(self)
    }
    fn cos(self) -> Self {
        f64::cos(self)
    }
    fn sqrt(self) -> Self {
        f64::sqrt(self)
    }
    fn atan2(self, x: Self) -> Self {
        f64::atan2(self, x)
    }
}

/// `Rot(axis, angle)·v` for a principal axis (0 = x, 1 = y, 2 = z), with
/// the MODEL.md §1 matrices `Rx`, `Ry`, `Rz`.
pub fn rotate<R: Real>(axis: usize, angle: R, v: [R; 3]) -> [R; 3] {
    let (s, c) = (angle.sin(), angle.cos());
    match axis {
        0 => [v[0], c * v[1] - s * v[2], s * v[1] + c * v[2]],
        1 => [c * v[0] + s * v[2], v[1], c * v[2] - s * v[0]],
        _ => [c * v[0] - s * v[1], s * v[0] + c * v[1], v[2]],
    }
}
