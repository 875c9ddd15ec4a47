//! Forward-mode dual numbers over any [`Scalar`]: `a + b·ε`, ε² = 0.
//!
//! Nesting (`Dual<Dual<f64>>`) gives exact second derivatives. The tests use
//! them as an independent oracle (Lagrange's equations in ordinary
//! coordinates, virtual work), and linearization uses them for exact
//! Jacobians of the very code the plant runs.

use core::ops::{Add, AddAssign, Div, Mul, MulAssign, Neg, Sub, SubAssign};

use crate::scalar::Scalar;

/// `re + eps·ε`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Dual<T> {
    /// Value.
    pub re: T,
    /// Derivative part.
    pub eps: T,
}

impl<T: Scalar> Dual<T> {
    /// A variable: value `re`, derivative 1.
    pub fn var(re: T) -> Self {
        Self { re, eps: T::one() }
    }
    /// A constant of type T.
    pub fn lift(re: T) -> Self {
        Self { re, eps: T::zero() }
    }
}

impl<T: Scalar> Add for Dual<T> {
    type Output = Self;
    fn add(self, o: Self) -> Self {
        Self {
            re: self.re + o.re,
            eps: self.eps + o.eps,
        }
    }
}
impl<T: Scalar> Sub for Dual<T> {
    type Output = Self;
    fn sub(self, o: Self) -> Self {
        Self {
            re: self.re - o.re,
            eps: self.eps - o.eps,
        }
    }
}
impl<T: Scalar> Mul for Dual<T> {
    type Output = Self;
    fn mul(self, o: Self) -> Self {
        Self {
            re: self.re * o.re,
            eps: self.re * o.eps + self.eps * o.re,
        }
    }
}
impl<T: Scalar> Div for Dual<T> {
    type Output = Self;
    fn div(self, o: Self) -> Self {
        let inv = T::one() / o.re;
        Self {
            re: self.re * inv,
            eps: (self.eps - self.re * inv * o.eps) * inv,
        }
    }
}
impl<T: Scalar> Neg for Dual<T> {
    type Output = Self;
    fn neg(self) -> Self {
        Self {
            re: -self.re,
            eps: -self.eps,
        }
    }
}
impl<T: Scalar> AddAssign for Dual<T> {
    fn add_assign(&mut self, o: Self) {
        *self = *self + o;
    }
}
impl<T: Scalar> SubAssign for Dual<T> {
    fn sub_assign(&mut self, o: Self) {
        *self = *self - o;
    }
}
impl<T: Scalar> MulAssign for Dual<T> {
    fn mul_assign(&mut self, o: Self) {
        *self = *self * o;
    }
}

/// Select a or b by a real comparison (derivatives follow the chosen branch).
fn pick<T: Scalar>(take_a: bool, a: Dual<T>, b: Dual<T>) -> Dual<T> {
    if take_a { a } else { b }
}

impl<T: Scalar + PartialOrd> Scalar for Dual<T> {
    fn cst(value: f64) -> Self {
        Self::lift(T::cst(value))
    }
    fn sin(self) -> Self {
        Self {
            re: self.re.sin(),
            eps: self.eps * self.re.cos(),
        }
    }
    fn cos(self) -> Self {
        Self {
            re: self.re.cos(),
            eps: -(self.eps * self.re.sin()),
        }
    }
    fn sqrt(self) -> Self {
        let r = self.re.sqrt();
        // At 0 along a direction that does not move the argument, the
        // derivative is 0, not 0/0: the lateral force of a wheel at full
        // drive saturation, `F_c·sqrt(1 − 1)`, is flat in every direction
        // that keeps it saturated.
        let eps = if self.eps == T::zero() {
            T::zero()
        } else {
            self.eps / (r + r)
        };
        Self { re: r, eps }
    }
    fn atan2(self, x: Self) -> Self {
        let d = x.re * x.re + self.re * self.re;
        Self {
            re: self.re.atan2(x.re),
            eps: (x.re * self.eps - self.re * x.eps) / d,
        }
    }
    fn atan(self) -> Self {
        Self {
            re: self.re.atan(),
            eps: self.eps / (T::one() + self.re * self.re),
        }
    }
    fn hypot(self, other: Self) -> Self {
        let h = self.re.hypot(other.re);
        Self {
            re: h,
            eps: (self.re * self.eps + other.re * other.eps) / h,
        }
    }
    fn exp(self) -> Self {
        let e = self.re.exp();
        Self {
            re: e,
            eps: self.eps * e,
        }
    }
    fn ln(self) -> Self {
        Self {
            re: self.re.ln(),
            eps: self.eps / self.re,
        }
    }
    fn abs(self) -> Self {
        pick(self.re >= T::zero(), self, -self)
    }
    fn max(self, other: Self) -> Self {
        pick(self.re >= other.re, self, other)
    }
    fn min(self, other: Self) -> Self {
        pick(self.re <= other.re, self, other)
    }
    fn copysign(self, sign: Self) -> Self {
        let a = self.abs();
        pick(sign.re >= T::zero(), a, -a)
    }
}

/// Ordered by value only, so that nested duals (`Dual<Dual<f64>>`) can pick
/// branches in `max`/`min`/`abs`.
impl<T: PartialOrd> PartialOrd for Dual<T> {
    fn partial_cmp(&self, other: &Self) -> Option<core::cmp::Ordering> {
        self.re.partial_cmp(&other.re)
    }
}
