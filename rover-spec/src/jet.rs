//! Truncated Taylor series ("jets"): evaluating the exact kinematics on
//! `y = y_c + ξ` gives the Taylor coefficients of every output exactly (to
//! rounding), which is the Taylor fit of MODEL.md §3 / paper eq. 33 for
//! every suspension kind, the four-bar linkage included.

use std::ops::{Add, Div, Mul, Neg, Sub};

use crate::real::Real;

/// Largest number of terms a fit may use.
pub const MAX_TERMS: usize = 12;

/// `Σ_p c[p]·ξ^p`, truncated after ξ^(MAX_TERMS−1).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Jet {
    /// Coefficients of ξ⁰ … ξ^(MAX_TERMS−1).
    pub c: [f64; MAX_TERMS],
}

impl Jet {
    /// The variable `y = centre + ξ`.
    pub fn variable(centre: f64) -> Self {
        let mut c = [0.0; MAX_TERMS];
        c[0] = centre;
        c[1] = 1.0;
        Jet { c }
    }

    /// The series' derivative d/dξ (the last coefficient becomes 0).
    #[allow(clippy::needless_range_loop)]
    fn derivative(self) -> Self {
        let mut c = [0.0; MAX_TERMS];
        for p in 1..MAX_TERMS {
            c[p - 1] = p as f64 * self.c[p];
        }
        Jet { c }
    }

    /// The antiderivative with constant term `c0`.
    #[allow(clippy::needless_range_loop)]
    fn integral(self, c0: f64) -> Self {
        let mut c = [0.0; MAX_TERMS];
        c[0] = c0;
        for p in 1..MAX_TERMS {
            c[p] = self.c[p - 1] / p as f64;
        }
        Jet { c }
    }

    /// Sine and cosine together: s' = c·a', c' = −s·a'.
    fn sin_cos(self) -> (Self, Self) {
        let mut s = [0.0; MAX_TERMS];
        let mut c = [0.0; MAX_TERMS];
        s[0] = self.c[0].sin();
        c[0] = self.c[0].cos();
        for n in 1..MAX_TERMS {
            let mut sn = 0.0;
            let mut cn = 0.0;
            for j in 1..=n {
                let ja = j as f64 * self.c[j];
                sn += ja * c[n - j];
                cn -= ja * s[n - j];
            }
            s[n] = sn / n as f64;
            c[n] = cn / n as f64;
        }
        (Jet { c: s }, Jet { c })
    }
}

impl Add for Jet {
    type Output = Jet;
    fn add(mut self, o: Jet) -> Jet {
        for (a, b) in self.c.iter_mut().zip(o.c) {
            *a += b;
        }
        self
    }
}

impl Sub for Jet {
    type Output = Jet;
    fn sub(mut self, o: Jet) -> Jet {
        for (a, b) in self.c.iter_mut().zip(o.c) {
            *a -= b;
        }
        self
    }
}

impl Neg for Jet {
    type Output = Jet;
    fn neg(mut self) -> Jet {
        for a in &mut self.c {
            *a = -*a;
        }
        self
    }
}

impl Mul for Jet {
    type Output = Jet;
    fn mul(self, o: Jet) -> Jet {
        let mut c = [0.0; MAX_TERMS];
        for (i, a) in self.c.iter().enumerate() {
            for (j, b) in o.c.iter().enumerate().take(MAX_TERMS - i) {
                c[i + j] += a * b;
            }
        }
        Jet { c }
    }
}

impl Div for Jet {
    type Output = Jet;
    /// q = a/b: b·q = a, so q_n = (a_n − Σ_{j≥1} b_j·q_{n−j}) / b_0.
    fn div(self, b: Jet) -> Jet {
        let mut q = [0.0; MAX_TERMS];
        for n in 0..MAX_TERMS {
            let mut v = self.c[n];
            for j in 1..=n {
                v -= b.c[j] * q[n - j];
            }
            q[n] = v / b.c[0];
        }
        Jet { c: q }
    }
}

impl Real for Jet {
    fn cst(v: f64) -> Self {
        let mut c = [0.0; MAX_TERMS];
        c[0] = v;
        Jet { c }
    }
    fn value(self) -> f64 {
        self.c[0]
    }
    fn sin(self) -> Self {
        self.sin_cos().0
    }
    fn cos(self) -> Self {
        self.sin_cos().1
    }
    /// s² = a: s_n = (a_n − Σ_{j=1}^{n−1} s_j·s_{n−j}) / (2·s_0).
    fn sqrt(self) -> Self {
        let mut s = [0.0; MAX_TERMS];
        s[0] = self.c[0].sqrt();
        for n in 1..MAX_TERMS {
            let mut v = self.c[n];
            for j in 1..n {
                v -= s[j] * s[n - j];
            }
            s[n] = v / (2.0 * s[0]);
        }
        Jet { c: s }
    }
    /// θ = atan2(y, x): θ' = (x·y' − y·x') / (x² + y²), θ_0 = atan2(y_0, x_0).
    fn atan2(self, x: Self) -> Self {
        let y = self;
        let rate = (x * y.derivative() - y * x.derivative()) / (x * x + y * y);
        rate.integral(y.c[0].atan2(x.c[0]))
    }
}
