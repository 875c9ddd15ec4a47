//! The linear solve `M·ẇ = b` of the generated right-hand side: LDLᵀ of
//! the suspension rows first, then the body's 6×6 Schur complement by two
//! 3×3 adjugates ([`block_solve`]).
//!
//! ```text
//! P·M·Pᵀ = L·D·Lᵀ on the first m columns,   P: order [y1 … ym, v, Ω]
//! v_k   = L_jk·D_k                      (shared by every row i > j)
//! D_j   = A_jj − Σ_{k<j} L_jk·v_k
//! L_ij  = (A_ij − Σ_{k<j} L_ik·v_k) · (1/D_j)
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

/// The first `p` columns of an LDLᵀ factorization (row-major N×N, rows
/// and columns taken in the elimination order).
struct Elimination<S> {
    /// Multipliers L, every row.
    l: Vec<S>,
    /// The same entries before division by their pivot, `U = L·D`: a
    /// product with U does not wait for the division (for a suspension row
    /// coupled to no other, U is M's own entry).
    u: Vec<S>,
    /// Pivots D.
    d: Vec<S>,
    /// Their reciprocals.
    inv: Vec<S>,
}

/// LDLᵀ of the first `p` columns of `a` (row-major N×N, symmetric) taken
/// in `order`.
fn eliminate<S: Scalar>(a: &[S], order: &[usize], p: usize) -> Elimination<S> {
    let n = order.len();
    let at = |i: usize, j: usize| a[order[i] * n + order[j]];
    let mut l = vec![S::zero(); n * n];
    let mut u = vec![S::zero(); n * n];
    let mut d = vec![S::zero(); n];
    let mut inv = vec![S::zero(); n];
    for j in 0..p {
        let mut dj = at(j, j);
        for k in 0..j {
            dj -= l[j * n + k] * u[j * n + k];
        }
        d[j] = dj;
        inv[j] = S::one() / dj;
        for i in j + 1..n {
            let mut s = at(i, j);
            for k in 0..j {
                s -= l[i * n + k] * u[j * n + k];
            }
            u[i * n + j] = s;
            l[i * n + j] = s * inv[j];
        }
    }
    Elimination { l, u, d, inv }
}

/// Solve `a·z = b` (`a` row-major N×N, symmetric positive definite, N ≥ 6)
/// by eliminating the suspension rows 6.. first ([`suspension_first`]
/// order) and solving the remaining 6×6 Schur complement of the body in
/// two 3×3 blocks with adjugates instead of six more LDLᵀ pivots:
/// ```text
/// S = [A  B; Bᵀ C],  X = A⁻¹·B,  C' = C − Bᵀ·X,  A⁻¹ = adj(A)/det(A)
/// x_Ω = C'⁻¹·(r_Ω − Xᵀ·r_v),  x_v = A⁻¹·(r_v − B·x_Ω)
/// ```
/// (Scaling C' by det A to take 1/det A off the chain measured slower.)
/// Same operations give or take a few, but the six pivots' chain of
/// dependent divisions becomes two independent 3×3 inversions whose
/// cofactors are computed side by side: the straight-line code is bound by
/// that chain's latency, not by its operation count. The pivots returned
/// are the LDLᵀ pivots in the same order, each as a (numerator,
/// denominator) pair (the body's six from the leading minors of A and C',
/// see `adjugate`), for the positive-definiteness check.
pub fn block_solve<S: Scalar>(a: &[S], b: &[S]) -> (Vec<S>, Vec<(S, S)>) {
    let n = b.len();
    let order = suspension_first(n);
    let p = n - 6;
    let at = |i: usize, j: usize| a[order[i] * n + order[j]];
    // LDLᵀ of the suspension rows, with the body rows' multipliers.
    let Elimination { l, u, d, inv } = eliminate(a, &order, p);
    // The body's Schur complement and right-hand side.
    let mut z: Vec<S> = order.iter().map(|&r| b[r]).collect();
    for i in 0..n {
        for k in 0..i.min(p) {
            let t = l[i * n + k] * z[k];
            z[i] -= t;
        }
    }
    let schur = |i: usize, k: usize| {
        let mut s = at(p + i, p + k);
        for j in 0..p {
            s -= l[(p + i) * n + j] * u[(p + k) * n + j];
        }
        s
    };
    let block = |r0: usize, c0: usize| -> [[S; 3]; 3] {
        core::array::from_fn(|i| core::array::from_fn(|k| schur(r0 + i, c0 + k)))
    };
    let (sa, sb, sc) = (block(0, 0), block(0, 3), block(3, 3));
    let (adj_a, det_a, piv_a) = adjugate(&sa);
    let inv_a = S::one() / det_a;
    // X = A⁻¹·B
    let x: [[S; 3]; 3] = core::array::from_fn(|i| {
        core::array::from_fn(|k| {
            (adj_a[i][0] * sb[0][k] + adj_a[i][1] * sb[1][k] + adj_a[i][2] * sb[2][k]) * inv_a
        })
    });
    let c2: [[S; 3]; 3] = core::array::from_fn(|i| {
        core::array::from_fn(|k| {
            sc[i][k] - (sb[0][i] * x[0][k] + sb[1][i] * x[1][k] + sb[2][i] * x[2][k])
        })
    });
    let (adj_c, det_c, piv_c) = adjugate(&c2);
    let inv_c = S::one() / det_c;
    let rv = [z[p], z[p + 1], z[p + 2]];
    let rw: [S; 3] = core::array::from_fn(|k| {
        z[p + 3 + k] - (x[0][k] * rv[0] + x[1][k] * rv[1] + x[2][k] * rv[2])
    });
    let xw: [S; 3] = core::array::from_fn(|i| {
        (adj_c[i][0] * rw[0] + adj_c[i][1] * rw[1] + adj_c[i][2] * rw[2]) * inv_c
    });
    let rv2: [S; 3] =
        core::array::from_fn(|i| rv[i] - (sb[i][0] * xw[0] + sb[i][1] * xw[1] + sb[i][2] * xw[2]));
    let xv: [S; 3] = core::array::from_fn(|i| {
        (adj_a[i][0] * rv2[0] + adj_a[i][1] * rv2[1] + adj_a[i][2] * rv2[2]) * inv_a
    });
    for k in 0..3 {
        z[p + k] = xv[k];
        z[p + 3 + k] = xw[k];
    }
    // Back to the suspension rows.
    for i in 0..p {
        z[i] *= inv[i];
    }
    for i in (0..p).rev() {
        for k in i + 1..n {
            let t = l[k * n + i] * z[k];
            z[i] -= t;
        }
    }
    let mut out = vec![S::zero(); n];
    for (q, &r) in order.iter().enumerate() {
        out[r] = z[q];
    }
    let pivots = d[..p]
        .iter()
        .map(|&v| (v, S::one()))
        .chain(piv_a)
        .chain(piv_c)
        .collect();
    (out, pivots)
}

/// Adjugate, determinant and LDLᵀ pivots of a symmetric 3×3 matrix, the
/// pivots as (numerator, denominator): the ratios of its leading minors,
/// `[a00/1, minor₂/a00, det/minor₂]`. Each pivot has the sign of its
/// numerator once the earlier ones are positive, so the check needs no
/// division; only a failing pivot's value is divided out, to report it.
fn adjugate<S: Scalar>(a: &[[S; 3]; 3]) -> ([[S; 3]; 3], S, [(S, S); 3]) {
    let c00 = a[1][1] * a[2][2] - a[1][2] * a[1][2];
    let c01 = a[0][2] * a[1][2] - a[0][1] * a[2][2];
    let c02 = a[0][1] * a[1][2] - a[0][2] * a[1][1];
    let c11 = a[0][0] * a[2][2] - a[0][2] * a[0][2];
    let c12 = a[0][1] * a[0][2] - a[0][0] * a[1][2];
    let c22 = a[0][0] * a[1][1] - a[0][1] * a[0][1];
    let det = a[0][0] * c00 + a[0][1] * c01 + a[0][2] * c02;
    let pivots = [(a[0][0], S::one()), (c22, a[0][0]), (det, c22)];
    (
        [[c00, c01, c02], [c01, c11, c12], [c02, c12, c22]],
        det,
        pivots,
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The plain LDLᵀ solve in `order` (every column eliminated): the
    /// reference the block solve is held against.
    fn ordered_ldlt_solve(a: &[f64], b: &[f64], order: &[usize]) -> (Vec<f64>, Vec<f64>) {
        let n = order.len();
        let Elimination { l, d, inv, .. } = eliminate(a, order, n);
        let mut z: Vec<f64> = order.iter().map(|&r| b[r]).collect();
        for i in 0..n {
            for k in 0..i {
                z[i] -= l[i * n + k] * z[k];
            }
        }
        for i in 0..n {
            z[i] *= inv[i];
        }
        for i in (0..n).rev() {
            for k in i + 1..n {
                z[i] -= l[k * n + i] * z[k];
            }
        }
        let mut out = vec![0.0; n];
        for (p, &r) in order.iter().enumerate() {
            out[r] = z[p];
        }
        (out, d)
    }

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

    #[test]
    fn the_block_solve_is_the_ldlt_solve() {
        // A 9×9 SPD matrix (body 6 + 3 suspension rows), filled and coupled.
        let n = 9;
        let mut a = vec![0.0; n * n];
        let mut seed = 7u64;
        let mut r = || {
            seed = seed
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (seed >> 11) as f64 / (1u64 << 53) as f64 - 0.5
        };
        let g: Vec<f64> = (0..n * n).map(|_| r()).collect();
        for i in 0..n {
            for k in 0..n {
                a[i * n + k] = (0..n).map(|j| g[i * n + j] * g[k * n + j]).sum::<f64>()
                    + if i == k { 1.0 } else { 0.0 };
            }
        }
        let b: Vec<f64> = (0..n).map(|_| r()).collect();
        let (z1, d1) = ordered_ldlt_solve(&a, &b, &suspension_first(n));
        let (z2, d2) = block_solve(&a, &b);
        for i in 0..n {
            assert!(
                (z1[i] - z2[i]).abs() < 1e-12,
                "row {i}: {} vs {}",
                z1[i],
                z2[i]
            );
            let d = d2[i].0 / d2[i].1;
            assert!(
                (d1[i] - d).abs() < 1e-12 * d1[i],
                "pivot {i}: {} vs {d}",
                d1[i]
            );
        }
    }
}
