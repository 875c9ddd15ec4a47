//! Dense LU factorization with partial pivoting, in place, for the Newton iteration matrix.

/// An `n × n` row-major matrix and, after [`Lu::factor`], its factors `P·A = L·U` (unit lower
/// `L` below the diagonal, `U` on and above it) and the row permutation. Storage is allocated
/// once in [`Lu::new`] (Golub & Van Loan, *Matrix Computations*, Algorithm 3.4.1).
#[derive(Debug, Clone)]
pub struct Lu {
    n: usize,
    a: Vec<f64>,
    pivots: Vec<usize>,
}

/// The matrix has a zero (or non-finite) pivot: it is singular to working precision.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Singular;

impl Lu {
    /// Room for an `n × n` matrix.
    pub fn new(n: usize) -> Self {
        Self {
            n,
            a: vec![0.0; n * n],
            pivots: vec![0; n],
        }
    }

    /// The matrix to fill (row-major) before [`Lu::factor`].
    pub fn matrix_mut(&mut self) -> &mut [f64] {
        &mut self.a
    }

    /// Factors `I − c·J` (`jac` row-major, `n × n`): the Newton matrix of the
    /// implicit methods.
    pub fn factor_shifted(&mut self, jac: &[f64], c: f64) -> Result<(), Singular> {
        let n = self.n;
        for (mi, ji) in self.a.iter_mut().zip(jac) {
            *mi = -c * ji;
        }
        for i in 0..n {
            self.a[i * n + i] += 1.0;
        }
        self.factor()
    }

    /// Factors the matrix in place.
    ///
    /// Written on row slices rather than indices: the elimination's inner
    /// loop `a_ij −= m·a_kj` over two distinct rows then compiles to packed
    /// SSE2 without bounds checks (each element is the same IEEE operation
    /// as in the indexed loop, so the factors are the same bits).
    pub fn factor(&mut self) -> Result<(), Singular> {
        let n = self.n;
        for k in 0..n {
            // The first row of largest magnitude in column k.
            let mut p = k;
            let mut best = self.a[k * n + k].abs();
            for (i, row) in self.a.chunks_exact(n).enumerate().skip(k + 1) {
                let v = row[k].abs();
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
                let (above, from_p) = self.a.split_at_mut(p * n);
                above[k * n..(k + 1) * n].swap_with_slice(&mut from_p[..n]);
            }
            let (upper, lower) = self.a.split_at_mut((k + 1) * n);
            let pivot_row = &upper[k * n..];
            let pivot = pivot_row[k];
            for row in lower.chunks_exact_mut(n) {
                let m = row[k] / pivot;
                row[k] = m;
                if m != 0.0 {
                    for (x, u) in row[k + 1..].iter_mut().zip(&pivot_row[k + 1..]) {
                        *x -= m * u;
                    }
                }
            }
        }
        Ok(())
    }

    /// Solves `A·x = b` with the factors, `b` overwritten by `x` (sums in
    /// the same order as `Σ_j` over increasing j, on row slices).
    pub fn solve(&self, b: &mut [f64]) {
        let n = self.n;
        for (k, &p) in self.pivots.iter().enumerate() {
            b.swap(k, p);
        }
        for (i, row) in self.a.chunks_exact(n).enumerate() {
            let (solved, rest) = b.split_at_mut(i);
            let mut s = rest[0];
            for (l, x) in row[..i].iter().zip(solved.iter()) {
                s -= l * x;
            }
            rest[0] = s;
        }
        for (i, row) in self.a.chunks_exact(n).enumerate().rev() {
            let (head, solved) = b.split_at_mut(i + 1);
            let mut s = head[i];
            for (u, x) in row[i + 1..].iter().zip(solved.iter()) {
                s -= u * x;
            }
            head[i] = s / row[i];
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A matrix needing a row swap: the solution of a 3×3 system with a known answer.
    #[test]
    fn solves_a_system_that_needs_pivoting() {
        let mut lu = Lu::new(3);
        lu.matrix_mut()
            .copy_from_slice(&[0.0, 2.0, 1.0, 1.0, 1.0, 1.0, 2.0, 1.0, 3.0]);
        lu.factor().unwrap();
        // x = (1, 2, 3): b = A·x.
        let mut b = [7.0, 6.0, 13.0];
        lu.solve(&mut b);
        for (got, want) in b.iter().zip([1.0, 2.0, 3.0]) {
            assert!((got - want).abs() < 1e-14, "{b:?}");
        }
    }

    /// Every pivot order on seeded 20 × 20 matrices (the size of a
    /// four-wheeled rover's state): the solution satisfies `A·x = b` to
    /// rounding, whichever rows the pivoting swaps.
    #[test]
    fn solves_random_systems_to_rounding() {
        let n = 20;
        let mut state = 0x2545_f491_4f6c_dd1d_u64;
        let mut uniform = move || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            (state >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
        };
        for _ in 0..20 {
            let a: Vec<f64> = (0..n * n).map(|_| uniform()).collect();
            let x: Vec<f64> = (0..n).map(|_| uniform()).collect();
            let b: Vec<f64> = a
                .chunks(n)
                .map(|row| row.iter().zip(&x).map(|(r, v)| r * v).sum())
                .collect();
            let mut lu = Lu::new(n);
            lu.matrix_mut().copy_from_slice(&a);
            lu.factor().unwrap();
            assert!(lu.pivots.iter().enumerate().any(|(k, &p)| p > k + 1));
            let mut got = b.clone();
            lu.solve(&mut got);
            for (row, bi) in a.chunks(n).zip(&b) {
                let r: f64 = row.iter().zip(&got).map(|(r, v)| r * v).sum();
                assert!((r - bi).abs() < 1e-12, "residual {} of {bi}", r - bi);
            }
        }
    }

    #[test]
    fn reports_a_singular_matrix() {
        let mut lu = Lu::new(2);
        lu.matrix_mut().copy_from_slice(&[1.0, 2.0, 2.0, 4.0]);
        assert_eq!(lu.factor(), Err(Singular));
    }
}
