//! Dense symmetric solve by LDLᵀ without pivoting (M is symmetric positive
//! definite). No square roots and no data-dependent branches, so the same
//! code traces into straight-line generated code.

use crate::scalar::Scalar;

/// Factor the row-major N×N symmetric matrix `a` in place into LDLᵀ (the
/// strict lower triangle holds L, the diagonal holds D) and solve `a·x = b`
/// in place in `b`. The pivots D stay on the diagonal of `a` for the
/// caller's positive-definiteness check (a generic scalar cannot be compared
/// here).
pub fn ldlt_solve<S: Scalar>(a: &mut [S], b: &mut [S], n: usize) {
    ldlt_factor(a, n);
    ldlt_substitute(a, b, n);
}

/// Factor the row-major N×N symmetric matrix `a` in place into LDLᵀ.
pub fn ldlt_factor<S: Scalar>(a: &mut [S], n: usize) {
    for j in 0..n {
        let mut d = a[j * n + j];
        for k in 0..j {
            d -= a[j * n + k] * a[j * n + k] * a[k * n + k];
        }
        a[j * n + j] = d;
        let inv = S::one() / d;
        for i in j + 1..n {
            let mut v = a[i * n + j];
            for k in 0..j {
                v -= a[i * n + k] * a[j * n + k] * a[k * n + k];
            }
            a[i * n + j] = v * inv;
        }
    }
}

/// Solve `a·x = b` in place in `b` with the factors of [`ldlt_factor`].
pub fn ldlt_substitute<S: Scalar>(a: &[S], b: &mut [S], n: usize) {
    // L·z = b
    for i in 0..n {
        for k in 0..i {
            let l = a[i * n + k];
            let bk = b[k];
            b[i] -= l * bk;
        }
    }
    // D·y = z
    for i in 0..n {
        b[i] = b[i] / a[i * n + i];
    }
    // Lᵀ·x = y
    for i in (0..n).rev() {
        for k in i + 1..n {
            let l = a[k * n + i];
            let bk = b[k];
            b[i] -= l * bk;
        }
    }
}
