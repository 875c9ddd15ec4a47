//! Dense linear algebra on row-major slices, sized once: the LU of the
//! prediction's `I − h·J`, solved against many right-hand sides at once
//! (the covariance's rows), and a Cholesky factor for the NEES.
//!
//! The solves work on whole rows (`row_i −= l·row_k`): contiguous,
//! vectorized loops; a multiplier that is zero (most of `I − h·J`'s
//! kinematic rows) skips its row.
//!
//! The covariance's kernels (its transition, a scalar update's
//! downdate) run in a copy compiled for x86-64-v4 when the processor has
//! it ([`rover_dynamics::cpu::x86_64_v4`], as the generated plants do):
//! eight lanes instead of SSE2's two. Rust fuses no product and sum on
//! its own, so both copies give the same bits.

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

    /// Factors the `n × n` matrix of entries `entry(i, j)`, `n` at most
    /// the size it was built with.
    pub(crate) fn factor_from(
        &mut self,
        n: usize,
        entry: impl Fn(usize, usize) -> f64,
    ) -> Result<(), Singular> {
        self.n = n;
        for i in 0..n {
            for j in 0..n {
                self.a[i * n + j] = entry(i, j);
            }
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
                swap_rows(&mut self.a[..n * n], n, k, p);
            }
            let (upper, lower) = self.a[..n * n].split_at_mut((k + 1) * n);
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

    /// `B ← A⁻¹·B`, `B` the first `n` rows of a row-major matrix of
    /// `cols` columns: every column solved at once, row by row.
    #[inline(always)]
    pub(crate) fn solve_rows(&self, b: &mut [f64], cols: usize) {
        let n = self.n;
        let b = &mut b[..n * cols];
        for (k, &p) in self.pivots[..n].iter().enumerate() {
            if p != k {
                swap_rows(b, cols, k, p);
            }
        }
        // L·Z = B, L unit lower: row_i −= Σ_k l_ik·row_k.
        for i in 1..n {
            let (done, rest) = b.split_at_mut(i * cols);
            combine(
                &mut rest[..cols],
                &self.a[i * n..i * n + i],
                done,
                cols,
                true,
            );
        }
        // U·X = Z: row_i = (row_i − Σ_k u_ik·row_k) / u_ii.
        for i in (0..n).rev() {
            let (head, tail) = b.split_at_mut((i + 1) * cols);
            let row_i = &mut head[i * cols..];
            combine(row_i, &self.a[i * n + i + 1..(i + 1) * n], tail, cols, true);
            let inv = 1.0 / self.a[i * n + i];
            row_i.iter_mut().for_each(|v| *v *= inv);
        }
    }
}

/// Swaps rows `k < p` of a row-major matrix of `cols` columns.
#[inline(always)]
fn swap_rows(m: &mut [f64], cols: usize, k: usize, p: usize) {
    let (upper, lower) = m.split_at_mut(p * cols);
    upper[k * cols..(k + 1) * cols].swap_with_slice(&mut lower[..cols]);
}

/// `target += Σ_k c_k·row_k` (`−=` when `subtract`), `row_k` the rows
/// of `sources` (`cols` columns), `c_k` = `coefficients[k]`, zeros
/// skipped: a block of columns held in registers while every row adds to
/// it, then stored once (a row's sequence of `axpy`s would load and
/// store the target for each); blocks of 8, then 4, 2 and 1 for the
/// rest. Each entry adds its terms in the order of `k`, as the `axpy`s
/// would: the same bits.
#[inline(always)]
pub(crate) fn combine(
    target: &mut [f64],
    coefficients: &[f64],
    sources: &[f64],
    cols: usize,
    subtract: bool,
) {
    let mut j0 = 0;
    while j0 + 8 <= cols {
        combine_block::<8>(target, coefficients, sources, cols, subtract, j0);
        j0 += 8;
    }
    if j0 + 4 <= cols {
        combine_block::<4>(target, coefficients, sources, cols, subtract, j0);
        j0 += 4;
    }
    if j0 + 2 <= cols {
        combine_block::<2>(target, coefficients, sources, cols, subtract, j0);
        j0 += 2;
    }
    if j0 < cols {
        combine_block::<1>(target, coefficients, sources, cols, subtract, j0);
    }
}

/// [`combine`] on the `W` columns from `j0`.
#[inline(always)]
fn combine_block<const W: usize>(
    target: &mut [f64],
    coefficients: &[f64],
    sources: &[f64],
    cols: usize,
    subtract: bool,
    j0: usize,
) {
    let target = &mut target[j0..j0 + W];
    let mut acc: [f64; W] = core::array::from_fn(|l| target[l]);
    for (k, &c) in coefficients.iter().enumerate() {
        if c == 0.0 {
            continue;
        }
        let c = if subtract { -c } else { c };
        let row = &sources[k * cols + j0..k * cols + j0 + W];
        for (a, s) in acc.iter_mut().zip(row) {
            *a += c * s;
        }
    }
    target.copy_from_slice(&acc);
}

/// `y += a·x`.
#[inline(always)]
pub(crate) fn axpy(y: &mut [f64], a: f64, x: &[f64]) {
    for (y, x) in y.iter_mut().zip(x) {
        *y += a * x;
    }
}

/// `m ← mᵀ`, `m` square `n × n`, row-major.
#[inline(always)]
pub(crate) fn transpose_in_place(m: &mut [f64], n: usize) {
    for i in 0..n {
        for j in i + 1..n {
            m.swap(i * n + j, j * n + i);
        }
    }
}

/// `m ← (m + mᵀ)/2`: rounding leaves `Φ·P·Φᵀ` a hair off symmetric.
#[inline(always)]
pub(crate) fn symmetrize(m: &mut [f64], n: usize) {
    for i in 0..n {
        for j in i + 1..n {
            let v = 0.5 * (m[i * n + j] + m[j * n + i]);
            m[i * n + j] = v;
            m[j * n + i] = v;
        }
    }
}

/// `p −= k·kᵀ` (`p` row-major `len × len`): a scalar update's
/// downdate. Each product `k_i·k_j` is `k_j·k_i`: `p` stays exactly
/// symmetric.
pub(crate) fn downdate(p: &mut [f64], k: &[f64], len: usize) {
    #[cfg(target_arch = "x86_64")]
    if rover_dynamics::cpu::x86_64_v4() {
        // SAFETY: the processor has the features (checked just above).
        return unsafe { downdate_v4(p, k, len) };
    }
    downdate_portable(p, k, len)
}

#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2,fma,avx512f,avx512vl")]
unsafe fn downdate_v4(p: &mut [f64], k: &[f64], len: usize) {
    downdate_portable(p, k, len)
}

#[inline(always)]
fn downdate_portable(p: &mut [f64], k: &[f64], len: usize) {
    for (row, &ki) in p[..len * len].chunks_exact_mut(len).zip(k) {
        for (pij, kj) in row.iter_mut().zip(k) {
            *pij -= ki * kj;
        }
    }
}

/// `u = Σ_k h_k·p[k, :]` over the rows `k` of `nonzero` (`p` symmetric:
/// `u = p·hᵀ` from whole rows).
pub(crate) fn gather(u: &mut [f64], p: &[f64], len: usize, h: &[f64], nonzero: &[usize]) {
    #[cfg(target_arch = "x86_64")]
    if rover_dynamics::cpu::x86_64_v4() {
        // SAFETY: the processor has the features (checked just above).
        return unsafe { gather_v4(u, p, len, h, nonzero) };
    }
    gather_portable(u, p, len, h, nonzero)
}

#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2,fma,avx512f,avx512vl")]
unsafe fn gather_v4(u: &mut [f64], p: &[f64], len: usize, h: &[f64], nonzero: &[usize]) {
    gather_portable(u, p, len, h, nonzero)
}

#[inline(always)]
fn gather_portable(u: &mut [f64], p: &[f64], len: usize, h: &[f64], nonzero: &[usize]) {
    u.iter_mut().for_each(|v| *v = 0.0);
    if 2 * nonzero.len() > len {
        combine(u, &h[..len], p, len, false);
        return;
    }
    for &k in nonzero {
        axpy(u, h[k], &p[k * len..(k + 1) * len]);
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
