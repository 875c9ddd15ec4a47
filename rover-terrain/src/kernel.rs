//! One-dimensional interpolation kernels shared by the grid interpolants.
//!
//! The bicubic interpolant is the tensor product of the Catmull–Rom cubic
//! (Keys' cubic convolution with a = −1/2; R. Keys, "Cubic convolution
//! interpolation for digital image processing", IEEE Trans. ASSP 29(6), 1981).
//! On the cell `[p0, p1]` with neighbours `p−1`, `p2` and local coordinate
//! `t ∈ [0, 1]`:
//! ```text
//! p(t) = w−1(t)·p−1 + w0(t)·p0 + w1(t)·p1 + w2(t)·p2
//! w−1 = (−t + 2t² − t³)/2     w0 = (2 − 5t² + 3t³)/2
//! w1  = ( t + 4t² − 3t³)/2    w2 = (−t² + t³)/2
//! ```
//! It is the cubic Hermite interpolant whose node slopes are central
//! differences `(p1 − p−1)/2`: it passes through the nodes, is C1 across
//! cells, and reproduces polynomials up to degree 2 exactly.

/// Catmull–Rom weights `[w−1, w0, w1, w2]` at `t` and their
/// `t`-derivatives: `rover_dynamics::bicubic`'s, which the contact search's
/// kept cells evaluate too.
pub(crate) use rover_dynamics::bicubic::catmull_rom;

/// The four stencil values `p(k−1) … p(k+2)` around cell `k` of a line of `n ≥ 2`
/// nodes, with ghost nodes beyond either end.
///
/// A ghost is the quadratic extrapolation `p(−1) = 3p(0) − 3p(1) + p(2)` (Keys'
/// boundary condition), which keeps quadratics exact up to the edge; a line of
/// only two nodes uses the linear `p(−1) = 2p(0) − p(1)`. `fetch(i)` is only
/// called with `i < n`; `k ≤ n − 2`.
#[inline]
pub(crate) fn stencil<T, F>(n: usize, k: usize, fetch: F) -> [T; 4]
where
    T: Copy + Ghost,
    F: Fn(usize) -> T,
{
    let p0 = fetch(k);
    let p1 = fetch(k + 1);
    let before = if k >= 1 {
        fetch(k - 1)
    } else if n >= 3 {
        T::quadratic(p0, p1, fetch(2))
    } else {
        T::linear(p0, p1)
    };
    let after = if k + 2 < n {
        fetch(k + 2)
    } else if n >= 3 {
        T::quadratic(p1, p0, fetch(n - 3))
    } else {
        T::linear(p1, p0)
    };
    [before, p0, p1, after]
}

/// Values that can be extrapolated to a ghost node (heights, or row sums with
/// their derivatives, which extrapolate the same way because interpolation is
/// linear in the node values).
pub(crate) trait Ghost {
    /// `3a − 3b + c`: the node before `a` on the quadratic through `a, b, c`.
    fn quadratic(a: Self, b: Self, c: Self) -> Self;
    /// `2a − b`: the node before `a` on the line through `a, b`.
    fn linear(a: Self, b: Self) -> Self;
}

impl Ghost for f64 {
    #[inline]
    fn quadratic(a: f64, b: f64, c: f64) -> f64 {
        3.0 * a - 3.0 * b + c
    }
    #[inline]
    fn linear(a: f64, b: f64) -> f64 {
        2.0 * a - b
    }
}

/// A bound `b ≥ 0` of a line that extrapolates like its nodes (the largest
/// slope of a stencil row, say): a ghost's bound is the ghost's combination
/// of the lines' bounds with every coefficient made positive (the triangle
/// inequality).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Bound(pub f64);

impl Ghost for Bound {
    #[inline]
    fn quadratic(a: Bound, b: Bound, c: Bound) -> Bound {
        Bound(3.0 * a.0 + 3.0 * b.0 + c.0)
    }
    #[inline]
    fn linear(a: Bound, b: Bound) -> Bound {
        Bound(2.0 * a.0 + b.0)
    }
}

impl<const N: usize> Ghost for [f64; N] {
    #[inline]
    fn quadratic(a: [f64; N], b: [f64; N], c: [f64; N]) -> [f64; N] {
        core::array::from_fn(|k| f64::quadratic(a[k], b[k], c[k]))
    }
    #[inline]
    fn linear(a: [f64; N], b: [f64; N]) -> [f64; N] {
        core::array::from_fn(|k| f64::linear(a[k], b[k]))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn weights_sum_to_one_and_derivatives_to_zero() {
        for k in 0..=10 {
            let t = f64::from(k) / 10.0;
            let (w, dw) = catmull_rom(t);
            assert!((w.iter().sum::<f64>() - 1.0).abs() < 1e-15);
            assert!(dw.iter().sum::<f64>().abs() < 1e-15);
        }
    }

    #[test]
    fn ghosts_extend_a_quadratic() {
        let q = |i: usize| {
            let x = i as f64;
            1.0 + 2.0 * x + 0.5 * x * x
        };
        let s = stencil(5, 0, q);
        assert_eq!(s, [1.0 - 2.0 + 0.5, q(0), q(1), q(2)]);
        let s = stencil(5, 3, q);
        assert_eq!(s[3], 1.0 + 10.0 + 12.5);
    }
}
