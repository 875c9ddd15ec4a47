//! The linear solve `M·ẇ = b` of the generated right-hand side: LDLᵀ of M
//! with the suspension coordinates eliminated first.
//!
//! ```text
//! P·M·Pᵀ = L·D·Lᵀ,   P: order [y1 … ym, v, Ω]
//! v_k   = L_jk·D_k                      (shared by every row i > j)
//! D_j   = A_jj − Σ_{k<j} L_jk·v_k
//! L_ij  = (A_ij − Σ_{k<j} L_ik·v_k) · (1/D_j)
//! L·z = P·b,  z ← z·(1/D),  Lᵀ·u = z,  ẇ = Pᵀ·u
//! ```
//! Why not `rover_dynamics::solve::ldlt_solve` as the generic plant: traced,
//! its order (v, Ω, then y) makes every suspension row fill in, and its
//! `L_ik·L_jk·D_k` products are not shared. The suspension block of M is
//! sparse (a coordinate couples only to the bodies it moves: diagonal for
//! independent arms), so eliminating it first leaves fewer, shorter
//! dependency chains of divisions; the structural zeros fold away in the
//! trace. The result equals the generic solve to rounding (the tests hold
//! it to 1e-12); M is positive definite iff every pivot is > 0, in any
//! order, so the generic plant's `SingularMass` check carries over (with
//! the row of the first failing pivot in this order).

use rover_dynamics::Scalar;

/// The elimination order: the suspension coordinates, then the body's six.
pub fn suspension_first(n: usize) -> Vec<usize> {
    (6..n).chain(0..6.min(n)).collect()
}

/// Solve `a·z = b` (`a` row-major N×N, symmetric) eliminating the rows
/// in `order`; returns z and the pivots D in elimination order.
pub fn ordered_ldlt_solve<S: Scalar>(a: &[S], b: &[S], order: &[usize]) -> (Vec<S>, Vec<S>) {
    let n = order.len();
    let at = |i: usize, j: usize| a[order[i] * n + order[j]];
    let mut l = vec![S::zero(); n * n];
    let mut d = vec![S::zero(); n];
    let mut inv = vec![S::zero(); n];
    for j in 0..n {
        let v: Vec<S> = (0..j).map(|k| l[j * n + k] * d[k]).collect();
        let mut dj = at(j, j);
        for (k, vk) in v.iter().enumerate() {
            dj -= l[j * n + k] * *vk;
        }
        d[j] = dj;
        inv[j] = S::one() / dj;
        for i in j + 1..n {
            let mut s = at(i, j);
            for (k, vk) in v.iter().enumerate() {
                s -= l[i * n + k] * *vk;
            }
            l[i * n + j] = s * inv[j];
        }
    }
    let mut z: Vec<S> = order.iter().map(|&r| b[r]).collect();
    for i in 0..n {
        for k in 0..i {
            let t = l[i * n + k] * z[k];
            z[i] -= t;
        }
    }
    for i in 0..n {
        z[i] *= inv[i];
    }
    for i in (0..n).rev() {
        for k in i + 1..n {
            let t = l[k * n + i] * z[k];
            z[i] -= t;
        }
    }
    let mut out = vec![S::zero(); n];
    for (p, &r) in order.iter().enumerate() {
        out[r] = z[p];
    }
    (out, d)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn solves_a_symmetric_positive_definite_system_in_any_order() {
        let a = [
            4.0, 1.0, 0.5, 0.0, //
            1.0, 3.0, 0.0, 0.2, //
            0.5, 0.0, 2.0, 0.1, //
            0.0, 0.2, 0.1, 1.0,
        ];
        let b = [1.0, -2.0, 0.5, 3.0];
        let mut dets = Vec::new();
        for order in [[0, 1, 2, 3], [2, 3, 0, 1], [3, 2, 1, 0]] {
            let (z, d) = ordered_ldlt_solve(&a, &b, &order);
            for r in 0..4 {
                let row: f64 = (0..4).map(|c| a[r * 4 + c] * z[c]).sum();
                assert!((row - b[r]).abs() < 1e-14, "{order:?} row {r}: {row}");
            }
            assert!(d.iter().all(|&p| p > 0.0));
            // The product of the pivots is det(A) in every order.
            dets.push(d.iter().product::<f64>());
        }
        assert!(
            dets.iter().all(|v| (v - dets[0]).abs() < 1e-12 * dets[0]),
            "{dets:?}"
        );
    }
}
