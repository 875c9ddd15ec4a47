//! Polynomial suspension kinematics (MODEL.md §3, paper eq. 32–34).
//!
//! ```text
//! u_j(y) = c_j + Σ_i Z_ij · [1, ξ_i, ξ_i², …, ξ_i^(k−1)]ᵀ,   ξ_i = y_i − y_ic
//! S_j[:, i]       = ∂u_j/∂y_i   = Z_ij · [0, 1, 2ξ_i, 3ξ_i², …]ᵀ      (eq. 34)
//! ∂S_j[:, i]/∂y_i = ∂²u_j/∂y_i² = Z_ij · [0, 0, 2, 6ξ_i, 12ξ_i², …]ᵀ
//! ```
//! Each term depends on one coordinate (the suspension library needs no
//! mixed terms), so the Hessian of u_j is diagonal in y.

use alloc::vec::Vec;

use crate::scalar::Scalar;

/// One coordinate's share of a polynomial: `Σ_p coeffs[p]·ξ^p`, ξ = y_coord − center.
#[derive(Clone, Debug, PartialEq)]
pub struct Term<T> {
    /// Index i of the coordinate y_i.
    pub coord: usize,
    /// Expansion centre y_ic (the paper's basis is 0; the rest value is better conditioned).
    pub center: f64,
    /// Coefficients of ξ⁰, ξ¹, … ξ^(k−1): the columns of Z_ij.
    pub coeffs: Vec<T>,
}

/// A vector polynomial in the suspension coordinates (u_j, in body components \[m\]).
#[derive(Clone, Debug, PartialEq, Default)]
pub struct PolyVec {
    /// Constant part c_j.
    pub constant: [f64; 3],
    /// Per-coordinate terms (at most one per coordinate after validation).
    pub terms: Vec<Term<[f64; 3]>>,
}

/// A scalar polynomial in the suspension coordinates (camber, steer, member angle).
#[derive(Clone, Debug, PartialEq, Default)]
pub struct ScalarPoly {
    /// Constant part.
    pub constant: f64,
    /// Per-coordinate terms.
    pub terms: Vec<Term<f64>>,
}

/// Value, first and second derivative of `Σ_p c[p]·ξ^p` at ξ (Horner).
#[inline]
fn horner<S: Scalar>(coeffs: &[f64], xi: S) -> (S, S, S) {
    let mut v = S::zero();
    let mut d1 = S::zero();
    let mut d2 = S::zero();
    for &c in coeffs.iter().rev() {
        d2 = d2 * xi + d1 * S::cst(2.0);
        d1 = d1 * xi + v;
        v = v * xi + S::cst(c);
    }
    (v, d1, d2)
}

impl PolyVec {
    /// A constant vector (a body fixed to the rover body).
    pub fn constant(c: [f64; 3]) -> Self {
        Self {
            constant: c,
            terms: Vec::new(),
        }
    }

    /// u(y).
    pub fn value<S: Scalar>(&self, y: &[S]) -> [S; 3] {
        self.eval(y, |_, _, _| {})
    }

    /// Value u(y), and for each term the coordinate, ∂u/∂y_i and ∂²u/∂y_i².
    /// Calls `each(coord, d1, d2)` once per term.
    pub fn eval<S: Scalar>(&self, y: &[S], mut each: impl FnMut(usize, [S; 3], [S; 3])) -> [S; 3] {
        let mut u = [
            S::cst(self.constant[0]),
            S::cst(self.constant[1]),
            S::cst(self.constant[2]),
        ];
        for t in &self.terms {
            let xi = y[t.coord] - S::cst(t.center);
            let mut d1 = [S::zero(); 3];
            let mut d2 = [S::zero(); 3];
            for k in 0..3 {
                let (v, a, b) = horner_component(&t.coeffs, k, xi);
                u[k] += v;
                d1[k] = a;
                d2[k] = b;
            }
            each(t.coord, d1, d2);
        }
        u
    }
}

/// Horner on one component of vector coefficients, without collecting.
#[inline]
fn horner_component<S: Scalar>(coeffs: &[[f64; 3]], k: usize, xi: S) -> (S, S, S) {
    let mut v = S::zero();
    let mut d1 = S::zero();
    let mut d2 = S::zero();
    for c in coeffs.iter().rev() {
        d2 = d2 * xi + d1 * S::cst(2.0);
        d1 = d1 * xi + v;
        v = v * xi + S::cst(c[k]);
    }
    (v, d1, d2)
}

impl ScalarPoly {
    /// A constant.
    pub fn constant(c: f64) -> Self {
        Self {
            constant: c,
            terms: Vec::new(),
        }
    }

    /// Whether the polynomial is identically zero.
    pub fn is_zero(&self) -> bool {
        self.constant == 0.0
            && self
                .terms
                .iter()
                .all(|t| t.coeffs.iter().all(|&c| c == 0.0))
    }

    /// Value at y.
    pub fn value<S: Scalar>(&self, y: &[S]) -> S {
        self.eval(y, |_, _, _| {})
    }

    /// Value at y; calls `each(coord, d1, d2)` with the first and second
    /// partial derivative for each term.
    pub fn eval<S: Scalar>(&self, y: &[S], mut each: impl FnMut(usize, S, S)) -> S {
        let mut v = S::cst(self.constant);
        for t in &self.terms {
            let xi = y[t.coord] - S::cst(t.center);
            let (a, b, c) = horner(&t.coeffs, xi);
            v += a;
            each(t.coord, b, c);
        }
        v
    }
}
