//! The history of the variable-order BDF/NDF method: backward differences of the solution.

use super::tableau::{BDF_GAMMA, BDF_MAX_ORDER};

/// Rows kept: `∇^0 … ∇^(k+2)` for the highest order `k`.
const ROWS: usize = BDF_MAX_ORDER + 3;

/// Backward differences `D_j = ∇^j y_n`, j = 0..=k+2, on the uniform grid of step `h`
/// ending at the current point (Shampine & Reichelt 1997, §2.1; Hairer & Wanner II, §III.1).
/// Row 0 is the solution itself. The interpolating polynomial of degree `k` through the last
/// `k + 1` points is, with `s = (t − t_n)/h` (Newton's backward formula):
/// ```text
/// P(t_n + s·h) = Σ_{j=0..k} D_j · φ_j(s),   φ_j(s) = s(s+1)…(s+j−1) / j!
/// ```
/// A step-size change re-samples it on the new grid (see [`BdfHistory::change_step`]).
#[derive(Debug, Clone)]
pub(crate) struct BdfHistory {
    n: usize,
    d: Vec<f64>,
    /// Current order k, 1..=5.
    pub order: usize,
    /// Step of the grid the differences refer to \[s\].
    pub h: f64,
    /// Steps taken at this step size since the last change.
    pub equal_steps: usize,
}

impl BdfHistory {
    /// Room for dimension `n`.
    pub(crate) fn new(n: usize) -> Self {
        Self {
            n,
            d: vec![0.0; ROWS * n],
            order: 1,
            h: 0.0,
            equal_steps: 0,
        }
    }

    /// Becomes a copy of `other` (same dimension), without allocating.
    pub(crate) fn copy_from(&mut self, other: &Self) {
        self.d.copy_from_slice(&other.d);
        self.order = other.order;
        self.h = other.h;
        self.equal_steps = other.equal_steps;
    }

    /// `∇^j y_n`.
    pub(crate) fn row(&self, j: usize) -> &[f64] {
        &self.d[j * self.n..(j + 1) * self.n]
    }

    fn row_mut(&mut self, j: usize) -> &mut [f64] {
        &mut self.d[j * self.n..(j + 1) * self.n]
    }

    /// Order 1 from `y` with derivative `f`, step `h`: `D_0 = y`, `D_1 = h·f`.
    pub(crate) fn start(&mut self, y: &[f64], f: &[f64], h: f64) {
        self.d.fill(0.0);
        self.row_mut(0).copy_from_slice(y);
        for (di, fi) in self.row_mut(1).iter_mut().zip(f) {
            *di = h * fi;
        }
        self.order = 1;
        self.h = h;
        self.equal_steps = 0;
    }

    /// The predictor `y^(0)_{n+1} = P(t_n + h) = Σ_{j=0..k} D_j` (φ_j(1) = 1).
    pub(crate) fn predict(&self, out: &mut [f64]) {
        out.fill(0.0);
        for j in 0..=self.order {
            for (o, dj) in out.iter_mut().zip(self.row(j)) {
                *o += dj;
            }
        }
    }

    /// The interpolating polynomial at `t_n + s·h` (`s ≤ 0` between the last points):
    /// `Σ_{j=0..k} D_j·φ_j(s)`.
    pub(crate) fn interpolate(&self, s: f64, out: &mut [f64]) {
        out.copy_from_slice(self.row(0));
        let mut phi = 1.0;
        for j in 1..=self.order {
            phi *= (s + j as f64 - 1.0) / j as f64;
            for (o, dj) in out.iter_mut().zip(self.row(j)) {
                *o += phi * dj;
            }
        }
    }

    /// `ψ = (1/α_k)·Σ_{m=1..k} γ_m·D_m`, the known part of the corrector equation.
    pub(crate) fn psi(&self, alpha: f64, out: &mut [f64]) {
        out.fill(0.0);
        for (m, gamma) in BDF_GAMMA.iter().enumerate().take(self.order + 1).skip(1) {
            let g = gamma / alpha;
            for (o, dm) in out.iter_mut().zip(self.row(m)) {
                *o += g * dm;
            }
        }
    }

    /// Re-samples the interpolating polynomial on a grid of step `h·factor`. With
    /// `R_ij(r) = φ_i(−r·j) = Π_{l=1..i} (l − 1 − r·j)/l` the values at the new grid points
    /// are `Rᵀ(r)·D`, and since `U = R(1)` satisfies `U² = I` the new differences are
    /// `D' = (R(r)·U)ᵀ·D` (Shampine & Reichelt 1997, §2.1). Rows above k are left as they are
    /// (stale until `k + 1` steps at the new size refresh them; order selection waits for that).
    #[allow(clippy::needless_range_loop)] // index notation mirrors the formulas
    pub(crate) fn change_step(&mut self, factor: f64) {
        let k = self.order;
        let r = resample_matrix(k, factor);
        let u = resample_matrix(k, 1.0);
        let mut ru = [[0.0; BDF_MAX_ORDER + 1]; BDF_MAX_ORDER + 1];
        for i in 0..=k {
            for j in 0..=k {
                ru[i][j] = (0..=k).map(|l| r[i][l] * u[l][j]).sum();
            }
        }
        let mut old = [0.0; BDF_MAX_ORDER + 1];
        for c in 0..self.n {
            for (j, o) in old.iter_mut().enumerate().take(k + 1) {
                *o = self.d[j * self.n + c];
            }
            for i in 0..=k {
                self.d[i * self.n + c] = (0..=k).map(|j| ru[j][i] * old[j]).sum();
            }
        }
        self.h *= factor;
        self.equal_steps = 0;
    }

    /// Accepts a step whose corrector moved the predictor by `d = y_{n+1} − y^(0)_{n+1}`:
    /// `∇^{k+1} y_{n+1} = d`, `∇^{k+2} y_{n+1} = d − ∇^{k+1} y_n`, and
    /// `∇^j y_{n+1} = ∇^j y_n + ∇^{j+1} y_{n+1}` for j = k..0.
    pub(crate) fn commit(&mut self, d: &[f64]) {
        let k = self.order;
        let n = self.n;
        let (low, high) = self.d.split_at_mut((k + 2) * n);
        let next = &mut low[(k + 1) * n..];
        for ((top, nx), dc) in high[..n].iter_mut().zip(next.iter_mut()).zip(d) {
            *top = dc - *nx;
            *nx = *dc;
        }
        for j in (0..=k).rev() {
            for c in 0..n {
                self.d[j * n + c] += self.d[(j + 1) * n + c];
            }
        }
        self.equal_steps += 1;
    }
}

/// `R_ij(r) = Π_{l=1..i} (l − 1 − r·j)/l` for i, j = 0..=k.
#[allow(clippy::needless_range_loop)] // index notation mirrors the formula
fn resample_matrix(k: usize, r: f64) -> [[f64; BDF_MAX_ORDER + 1]; BDF_MAX_ORDER + 1] {
    let mut m = [[0.0; BDF_MAX_ORDER + 1]; BDF_MAX_ORDER + 1];
    for j in 0..=k {
        m[0][j] = 1.0;
        for i in 1..=k {
            let l = i as f64;
            m[i][j] = m[i - 1][j] * (l - 1.0 - r * j as f64) / l;
        }
    }
    m
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Backward differences of `p` on the grid `t_n − j·h`, j = 0..=k.
    fn differences(p: impl Fn(f64) -> f64, t_n: f64, h: f64, k: usize) -> Vec<f64> {
        let mut v: Vec<f64> = (0..=k).map(|j| p(t_n - j as f64 * h)).collect();
        let mut out = vec![v[0]];
        for _ in 0..k {
            v = v.windows(2).map(|w| w[0] - w[1]).collect();
            out.push(v[0]);
        }
        out
    }

    /// A cubic is represented exactly by order-3 differences, so re-sampling on another grid
    /// must reproduce the differences computed directly on that grid, for shrinking and
    /// growing steps alike.
    #[test]
    fn change_step_resamples_the_interpolating_polynomial_exactly() {
        let p = |t: f64| 1.0 + 2.0 * t - t * t + 0.5 * t * t * t;
        let (t_n, h, k) = (0.7, 0.1, 3);
        for factor in [0.37, 2.5] {
            let mut hist = BdfHistory::new(1);
            for (j, dj) in differences(p, t_n, h, k).into_iter().enumerate() {
                hist.d[j] = dj;
            }
            hist.order = k;
            hist.h = h;
            hist.change_step(factor);
            let want = differences(p, t_n, h * factor, k);
            for (j, w) in want.iter().enumerate() {
                assert!(
                    (hist.row(j)[0] - w).abs() < 1e-13,
                    "factor {factor}, row {j}: {} vs {w}",
                    hist.row(j)[0]
                );
            }
            assert!((hist.h - h * factor).abs() < 1e-15);
        }
    }

    /// The interpolant of order k reproduces a degree-k polynomial between the grid points.
    #[test]
    fn interpolant_reproduces_a_polynomial_of_the_order() {
        let p = |t: f64| 1.0 - 2.0 * t + 0.5 * t * t * t;
        let (t_n, h, k) = (2.0, 0.3, 3);
        let mut hist = BdfHistory::new(1);
        for (j, dj) in differences(p, t_n, h, k).into_iter().enumerate() {
            hist.d[j] = dj;
        }
        hist.order = k;
        for s in [0.0, -0.25, -0.5, -1.0, -2.7] {
            let mut out = [0.0];
            hist.interpolate(s, &mut out);
            let want = p(t_n + s * h);
            assert!((out[0] - want).abs() < 1e-13, "s {s}: {} vs {want}", out[0]);
        }
    }

    /// The predictor of order k extrapolates a degree-k polynomial exactly.
    #[test]
    fn predictor_extrapolates_a_polynomial_of_the_order() {
        let p = |t: f64| 3.0 - t + 4.0 * t * t;
        let mut hist = BdfHistory::new(1);
        for (j, dj) in differences(p, 1.0, 0.25, 2).into_iter().enumerate() {
            hist.d[j] = dj;
        }
        hist.order = 2;
        let mut out = [0.0];
        hist.predict(&mut out);
        assert!(
            (out[0] - p(1.25)).abs() < 1e-13,
            "{} vs {}",
            out[0],
            p(1.25)
        );
    }
}
