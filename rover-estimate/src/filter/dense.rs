//! Dense linear algebra on row-major slices, sized once: the LU of the
//! prediction's `I − h·J`, solved against many right-hand sides at once
//! (the covariance's rows), and a Cholesky factor for the NEES.
//!
//! The solves work on whole rows (`row_i −= l·row_k`): contiguous,
//! vectorized loops; a multiplier that is zero (most of `I − h·J`'s
//! kinematic rows) skips its row.

use alloc::vec;
use alloc::vec::Vec;

/// `A = I − h·J` factored as `P·A = L·U` (partial pivoting), in place.
#[derive(Clone, Debug)]
pub(crate) struct Lu {
    n: usize,
    a: Vec<f64>,
    pivots: Vec<usize>,
}

/// A pivot that is zero or not finite: the matrix is singular.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Singular;

impl Lu {
    /// Room for an `n × n` matrix.
    pub(crate) fn new(n: usize) -> Self {
        Self {
            n,
            a: vec![0.0; n * n],
            pivots: vec![0; n],
        }
    }

    /// Factors `I − h·jac` (`jac` row-major `n × n`).
    pub(crate) fn factor_shifted(&mut self, jac: &[f64], h: f64) -> Result<(), Singular> {
        let n = self.n;
        for (a, j) in self.a.iter_mut().zip(jac) {
            *a = -h * j;
        }
        for i in 0..n {
            self.a[i * n + i] += 1.0;
        }
        self.factor()
    }

    fn factor(&mut self) -> Result<(), Singular> {
        let n = self.n;
        for k in 0..n {
            let mut p = k;
            let mut best = self.a[k * n + k].abs();
            for i in k + 1..n {
                let v = self.a[i * n + k].abs();
                if v > best {
                    best = v;
                    p = i;
                }
            }
            if best == 0.0 || !best.is_finite() {
                return Err(Singular);
            }
            self.pivots[k] = p;
            if p != k {
                for j in 0..n {
                    self.a.swap(k * n + j, p * n + j);
                }
            }
            let (upper, lower) = self.a.split_at_mut((k + 1) * n);
            let row_k = &upper[k * n..];
            let pivot = row_k[k];
            for row_i in lower.chunks_exact_mut(n) {
                if row_i[k] == 0.0 {
                    continue;
                }
                let m = row_i[k] / pivot;
                row_i[k] = m;
                for (a, b) in row_i[k + 1..].iter_mut().zip(&row_k[k + 1..]) {
                    *a -= m * b;
                }
            }
        }
        Ok(())
    }

    /// `b ← A⁻¹·b`, one vector.
    pub(crate) fn solve(&self, b: &mut [f64]) {
        self.solve_rows(b, 1);
    }

    /// `B ← A⁻¹·B`, `B` the first `n` rows of a row-major matrix of
    /// `cols` columns: every column solved at once, row by row.
    pub(crate) fn solve_rows(&self, b: &mut [f64], cols: usize) {
        let n = self.n;
        let b = &mut b[..n * cols];
        for (k, &p) in self.pivots.iter().enumerate() {
            if p != k {
                for j in 0..cols {
                    b.swap(k * cols + j, p * cols + j);
                }
            }
        }
        // L·Z = B, L unit lower.
        for i in 1..n {
            let (done, rest) = b.split_at_mut(i * cols);
            let row_i = &mut rest[..cols];
            for (k, &l) in self.a[i * n..i * n + i].iter().enumerate() {
                if l != 0.0 {
                    axpy(row_i, -l, &done[k * cols..(k + 1) * cols]);
                }
            }
        }
        // U·X = Z.
        for i in (0..n).rev() {
            let (head, tail) = b.split_at_mut((i + 1) * cols);
            let row_i = &mut head[i * cols..];
            for (k, &u) in self.a[i * n + i + 1..(i + 1) * n].iter().enumerate() {
                if u != 0.0 {
                    axpy(row_i, -u, &tail[k * cols..(k + 1) * cols]);
                }
            }
            let inv = 1.0 / self.a[i * n + i];
            row_i.iter_mut().for_each(|v| *v *= inv);
        }
    }
}

/// `y += a·x`.
pub(crate) fn axpy(y: &mut [f64], a: f64, x: &[f64]) {
    for (y, x) in y.iter_mut().zip(x) {
        *y += a * x;
    }
}

/// `m ← mᵀ`, `m` square `n × n`, row-major.
pub(crate) fn transpose_in_place(m: &mut [f64], n: usize) {
    for i in 0..n {
        for j in i + 1..n {
            m.swap(i * n + j, j * n + i);
        }
    }
}

/// `m ← (m + mᵀ)/2`: rounding leaves `Φ·P·Φᵀ` a hair off symmetric.
pub(crate) fn symmetrize(m: &mut [f64], n: usize) {
    for i in 0..n {
        for j in i + 1..n {
            let v = 0.5 * (m[i * n + j] + m[j * n + i]);
            m[i * n + j] = v;
            m[j * n + i] = v;
        }
    }
}

/// Factors the symmetric positive definite `a` (`n × n`, row-major) as
/// `L·Lᵀ` in its lower triangle; `Err(k)` at the first pivot `k` that is
/// not positive.
pub(crate) fn cholesky(a: &mut [f64], n: usize) -> Result<(), usize> {
    for j in 0..n {
        let mut d = a[j * n + j];
        for k in 0..j {
            d -= a[j * n + k] * a[j * n + k];
        }
        if !(d.is_finite() && d > 0.0) {
            return Err(j);
        }
        let d = libm::sqrt(d);
        a[j * n + j] = d;
        for i in j + 1..n {
            let mut s = a[i * n + j];
            for k in 0..j {
                s -= a[i * n + k] * a[j * n + k];
            }
            a[i * n + j] = s / d;
        }
    }
    Ok(())
}

/// `|L⁻¹·b|²` = `bᵀ·A⁻¹·b` with `A = L·Lᵀ` from [`cholesky`]; `b` is
/// overwritten by `L⁻¹·b`.
pub(crate) fn cholesky_quadratic(l: &[f64], n: usize, b: &mut [f64]) -> f64 {
    let mut sum = 0.0;
    for i in 0..n {
        let mut s = b[i];
        for k in 0..i {
            s -= l[i * n + k] * b[k];
        }
        b[i] = s / l[i * n + i];
        sum += b[i] * b[i];
    }
    sum
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lu_solves_many_columns_at_once() {
        let jac = [0.5, -2.0, 1.0, 3.0, 0.1, 0.0, -1.0, 4.0, 2.0];
        let h = 0.7;
        let mut lu = Lu::new(3);
        lu.factor_shifted(&jac, h).unwrap();
        let b0 = [1.0, 2.0, 3.0, -1.0, 0.5, 0.25];
        let mut x = b0;
        lu.solve_rows(&mut x, 2);
        for c in 0..2 {
            for i in 0..3 {
                let ax: f64 = (0..3)
                    .map(|k| {
                        let a = f64::from(u8::from(i == k)) - h * jac[i * 3 + k];
                        a * x[k * 2 + c]
                    })
                    .sum();
                assert!((ax - b0[i * 2 + c]).abs() < 1e-14);
            }
        }
    }

    #[test]
    fn cholesky_gives_the_quadratic_form() {
        let mut a = [4.0, 2.0, 2.0, 3.0];
        let a0 = a;
        cholesky(&mut a, 2).unwrap();
        let mut b = [1.0, -2.0];
        let q = cholesky_quadratic(&a, 2, &mut b);
        // a⁻¹ = [[3, −2], [−2, 4]]/8.
        let expected = (3.0 * 1.0 + 2.0 * 2.0 * 2.0 + 4.0 * 4.0) / 8.0;
        assert!((q - expected).abs() < 1e-14, "{q} {expected} {a0:?}");
        assert_eq!(cholesky(&mut [1.0, 2.0, 2.0, 1.0], 2), Err(1));
    }
}
