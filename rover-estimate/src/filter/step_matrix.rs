//! The prediction's matrix `A = I − h·J`, factored by blocks of the
//! state `y = [x; w]` (`w` with the spins): the coordinates' rates
//! `ẋ = B(x)·w` depend on few coordinates (the attitude's, MODEL.md §2),
//! so the coordinates' block `D = I − h·J_xx` is the identity but for a
//! few columns, and eliminating it leaves a dense system of `w`'s size
//! only (the Schur complement), half the state:
//! ```text
//! A = [D, −h·J_xw; −h·J_wx, I − h·J_ww]
//! D⁻¹·r:  z_C = (I − h·J_xx[C, C])⁻¹·r_C,  z = r + h·J_xx[:, C]·z_C
//!         (C: the columns of J_xx that are not zero)
//! M = h·D⁻¹·J_xw,   K = I − h·J_ww − h·J_wx·M
//! A·[z_x; z_w] = [r_x; r_w]:  y = D⁻¹·r_x,  z_w = K⁻¹·(r_w + h·J_wx·y),
//!                              z_x = y + M·z_w
//! ```
//! A factorization costs about `(N + |C|)³/3` instead of `(2N)³/3`, a
//! solve `(N² + 2N²)` per column instead of `4N²`, and `M`'s zeros (B's)
//! are skipped. D is well conditioned (near I at the steps a filter
//! takes), so eliminating it first needs no pivoting; K is factored with
//! partial pivoting. A model whose `J_xx` is dense in more than half its
//! columns is factored whole instead.

use alloc::vec;
use alloc::vec::Vec;

use super::dense::{Lu, Singular, axpy, combine};

/// `I − h·J`, factored (module docs).
#[derive(Clone, Debug)]
pub(crate) struct StepMatrix {
    /// The coordinates' count N (the first block).
    n: usize,
    /// The state's length.
    dim: usize,
    /// Whether the blocks are used (else `whole`).
    by_blocks: bool,
    /// The columns C of `J_xx` that are not zero, the first `coupled`.
    columns: Vec<usize>,
    coupled: usize,
    /// `h·J_xx[:, C]`, `n × coupled`.
    jxc: Vec<f64>,
    /// `I − h·J_xx[C, C]`, factored.
    small: Lu,
    /// `M = h·D⁻¹·J_xw`, `n × w`.
    m: Vec<f64>,
    /// `h·J_wx`, `w × n`.
    jwx: Vec<f64>,
    /// `K`, factored.
    schur: Lu,
    /// `K` before its factorization, and `C`'s rows during a solve.
    scratch: Vec<f64>,
    /// The whole matrix, when the blocks do not pay.
    whole: Lu,
}

impl StepMatrix {
    /// Room for a state of `dim` whose first `n` entries are the
    /// coordinates, solved against up to `cols` columns at once.
    pub(crate) fn new(n: usize, dim: usize, cols: usize) -> Self {
        let w = dim - n;
        Self {
            n,
            dim,
            by_blocks: true,
            columns: vec![0; n],
            coupled: 0,
            jxc: vec![0.0; n * n],
            small: Lu::new(n),
            m: vec![0.0; n * w],
            jwx: vec![0.0; w * n],
            schur: Lu::new(w),
            scratch: vec![0.0; (w * w).max(n * cols)],
            whole: Lu::new(dim),
        }
    }

    /// Factors `I − h·jac` (`jac` row-major `dim × dim`).
    pub(crate) fn factor(&mut self, jac: &[f64], h: f64) -> Result<(), Singular> {
        let (n, dim) = (self.n, self.dim);
        let w = dim - n;
        self.coupled = 0;
        for c in 0..n {
            if (0..n).any(|i| jac[i * dim + c] != 0.0) {
                self.columns[self.coupled] = c;
                self.coupled += 1;
            }
        }
        self.by_blocks = 2 * self.coupled <= n;
        if !self.by_blocks {
            return self.whole.factor_shifted(jac, h);
        }
        let (columns, coupled) = (&self.columns[..self.coupled], self.coupled);
        self.small.factor_from(coupled, |a, b| {
            f64::from(u8::from(a == b)) - h * jac[columns[a] * dim + columns[b]]
        })?;
        for i in 0..n {
            for (a, &c) in columns.iter().enumerate() {
                self.jxc[i * coupled + a] = h * jac[i * dim + c];
            }
            for j in 0..w {
                self.m[i * w + j] = h * jac[i * dim + n + j];
            }
        }
        for k in 0..w {
            for i in 0..n {
                self.jwx[k * n + i] = h * jac[(n + k) * dim + i];
            }
        }
        let mut m = core::mem::take(&mut self.m);
        self.apply_d_inverse(&mut m, w);
        self.m = m;
        // K = I − h·J_ww − h·J_wx·M, row by row.
        let k = &mut self.scratch[..w * w];
        for i in 0..w {
            let row = &mut k[i * w..(i + 1) * w];
            for (j, v) in row.iter_mut().enumerate() {
                *v = f64::from(u8::from(i == j)) - h * jac[(n + i) * dim + n + j];
            }
            combine(row, &self.jwx[i * n..(i + 1) * n], &self.m, w, true);
        }
        let k = &self.scratch;
        self.schur.factor_from(w, |i, j| k[i * w + j])
    }

    /// `rows ← D⁻¹·rows`, `rows` the first `n` rows of a row-major
    /// matrix of `cols` columns.
    #[inline(always)]
    fn apply_d_inverse(&mut self, rows: &mut [f64], cols: usize) {
        let (n, coupled) = (self.n, self.coupled);
        if coupled == 0 {
            return;
        }
        let columns = &self.columns[..coupled];
        // z_C = (I − h·J_xx[C, C])⁻¹·r_C.
        let gathered = &mut self.scratch[..coupled * cols];
        for (a, &c) in columns.iter().enumerate() {
            gathered[a * cols..(a + 1) * cols].copy_from_slice(&rows[c * cols..(c + 1) * cols]);
        }
        self.small.solve_rows(gathered, cols);
        for (a, &c) in columns.iter().enumerate() {
            rows[c * cols..(c + 1) * cols].copy_from_slice(&gathered[a * cols..(a + 1) * cols]);
        }
        // z_i = r_i + h·J_xx[i, C]·z_C for the rows outside C.
        for i in 0..n {
            if columns.contains(&i) {
                continue;
            }
            for (a, &c) in columns.iter().enumerate() {
                let v = self.jxc[i * coupled + a];
                if v != 0.0 {
                    let (head, tail) = rows.split_at_mut(i.max(c) * cols);
                    let (row_i, row_c) = if i < c {
                        (&mut head[i * cols..(i + 1) * cols], &tail[..cols])
                    } else {
                        (&mut tail[..cols], &head[c * cols..(c + 1) * cols])
                    };
                    axpy(row_i, v, row_c);
                }
            }
        }
    }

    /// `B ← A⁻¹·B`, `B` the first `dim` rows of a row-major matrix of
    /// `cols` columns (at most the `cols` it was built for).
    #[inline(always)]
    pub(crate) fn solve_rows(&mut self, b: &mut [f64], cols: usize) {
        if !self.by_blocks {
            self.whole.solve_rows(b, cols);
            return;
        }
        let (n, w) = (self.n, self.dim - self.n);
        let (x_rows, rest) = b.split_at_mut(n * cols);
        let w_rows = &mut rest[..w * cols];
        self.apply_d_inverse(x_rows, cols);
        for i in 0..w {
            let row = &mut w_rows[i * cols..(i + 1) * cols];
            combine(row, &self.jwx[i * n..(i + 1) * n], x_rows, cols, false);
        }
        self.schur.solve_rows(w_rows, cols);
        for i in 0..n {
            let row = &mut x_rows[i * cols..(i + 1) * cols];
            combine(row, &self.m[i * w..(i + 1) * w], w_rows, cols, false);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A rover-shaped Jacobian: `ẋ = B(x)·w` (the attitude's columns of
    /// J_xx and B's blocks), `ẇ` rows dense and stiff.
    fn rover_shaped(n: usize) -> Vec<f64> {
        let dim = 2 * n;
        let mut jac = vec![0.0; dim * dim];
        let mut v = 0.37;
        let mut next = || {
            v = (v * 7.13 + 0.11) % 1.0;
            v - 0.5
        };
        for i in 0..6 {
            for c in 3..6 {
                jac[i * dim + c] = next();
            }
        }
        for i in 0..n {
            for j in 0..n {
                let block = (i < 3 && j < 3) || ((3..6).contains(&i) && (3..6).contains(&j));
                if block || (i >= 6 && i == j) {
                    jac[i * dim + n + j] = if i == j && i >= 6 { 1.0 } else { next() };
                }
            }
        }
        for i in n..dim {
            for j in 0..dim {
                jac[i * dim + j] = 3000.0 * next();
            }
        }
        jac
    }

    #[test]
    fn blocks_solve_as_the_whole_matrix_does() {
        let (n, cols, h) = (10, 7, 0.01);
        let dim = 2 * n;
        let jac = rover_shaped(n);
        let mut blocks = StepMatrix::new(n, dim, cols);
        blocks.factor(&jac, h).unwrap();
        assert!(blocks.by_blocks && blocks.coupled == 3);
        let mut whole = Lu::new(dim);
        whole.factor_shifted(&jac, h).unwrap();
        let b: Vec<f64> = (0..dim * cols)
            .map(|i| ((i * 37 % 11) as f64) - 5.0)
            .collect();
        let (mut x1, mut x2) = (b.clone(), b);
        blocks.solve_rows(&mut x1, cols);
        whole.solve_rows(&mut x2, cols);
        let scale = x2.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        for (a, b) in x1.iter().zip(&x2) {
            assert!((a - b).abs() < 1e-12 * scale, "{a} {b}");
        }
    }
}
