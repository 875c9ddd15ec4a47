//! The scalar the equations are written over.
//!
//! Every equation of the model is written once, generic over [`Scalar`]. The
//! generic plant runs it with `f64`; the code generator runs it with a symbolic
//! type that records an expression graph and prints straight-line Rust; tests
//! run it with dual numbers for exact derivatives. So the trait holds only what
//! the physics needs, and nothing that branches on a value: a traced program
//! cannot follow a data-dependent `if`, so singular points are handled with
//! `max`, `min` and `copysign` instead, and the traced code stays one
//! straight line.

use core::fmt::Debug;
use core::ops::{Add, AddAssign, Div, Mul, MulAssign, Neg, Sub, SubAssign};

/// A real number as the equations see it.
pub trait Scalar:
    Copy
    + Debug
    + Add<Output = Self>
    + Sub<Output = Self>
    + Mul<Output = Self>
    + Div<Output = Self>
    + Neg<Output = Self>
    + AddAssign
    + SubAssign
    + MulAssign
{
    /// A constant of the model (a mass, a length, a polynomial coefficient).
    fn cst(value: f64) -> Self;
    /// `0`.
    fn zero() -> Self {
        Self::cst(0.0)
    }
    /// `1`.
    fn one() -> Self {
        Self::cst(1.0)
    }
    /// Sine.
    fn sin(self) -> Self;
    /// Cosine.
    fn cos(self) -> Self;
    /// Square root.
    fn sqrt(self) -> Self;
    /// `atan2(self, x)`, the angle of the point (x, self).
    fn atan2(self, x: Self) -> Self;
    /// Exponential.
    fn exp(self) -> Self;
    /// Natural logarithm.
    fn ln(self) -> Self;
    /// Absolute value.
    fn abs(self) -> Self;
    /// Larger of two values.
    fn max(self, other: Self) -> Self;
    /// Smaller of two values.
    fn min(self, other: Self) -> Self;
    /// `|self|` with the sign of `sign`.
    fn copysign(self, sign: Self) -> Self;
    /// Square, written as a product (never `powf`).
    fn sq(self) -> Self {
        self * self
    }
    /// Arctangent, as `atan2(self, 1)` unless the scalar has its own.
    fn atan(self) -> Self {
        self.atan2(Self::one())
    }
    /// `sqrt(self² + other²)`, written out unless the scalar has its own
    /// (f64's avoids overflow and rounds once).
    fn hypot(self, other: Self) -> Self {
        (self * self + other * other).sqrt()
    }
    /// `self` to the power `e`, a constant, as `exp(e·ln self)` for
    /// `self > 0` (a soil's pressure–sinkage exponent): one form that the
    /// generator traces and differentiates like the rest.
    fn powf(self, e: f64) -> Self {
        (Self::cst(e) * self.ln()).exp()
    }
}

impl Scalar for f64 {
    #[inline(always)]
    fn cst(value: f64) -> Self {
        value
    }
    #[inline(always)]
    fn sin(self) -> Self {
        libm::sin(self)
    }
    #[inline(always)]
    fn cos(self) -> Self {
        libm::cos(self)
    }
    #[inline(always)]
    fn sqrt(self) -> Self {
        libm::sqrt(self)
    }
    #[inline(always)]
    fn atan2(self, x: Self) -> Self {
        libm::atan2(self, x)
    }
    #[inline(always)]
    fn exp(self) -> Self {
        libm::exp(self)
    }
    #[inline(always)]
    fn ln(self) -> Self {
        libm::log(self)
    }
    #[inline(always)]
    fn abs(self) -> Self {
        f64::abs(self)
    }
    #[inline(always)]
    fn max(self, other: Self) -> Self {
        f64::max(self, other)
    }
    #[inline(always)]
    fn min(self, other: Self) -> Self {
        f64::min(self, other)
    }
    #[inline(always)]
    fn copysign(self, sign: Self) -> Self {
        f64::copysign(self, sign)
    }
    #[inline(always)]
    fn atan(self) -> Self {
        libm::atan(self)
    }
    #[inline(always)]
    fn hypot(self, other: Self) -> Self {
        libm::hypot(self, other)
    }
}
