//! Dense LU factorization with partial pivoting, in place, for the Newton iteration matrix.

/// An `n × n` row-major matrix and, after [`Lu::factor`], its factors `P·A = L·U` (unit lower
/// `L` below the diagonal, `U` on and above it) and the row permutation. Storage is allocated
/// once in [`Lu::new`] (Golub & Van Loan, *Matrix Computations*, Algorithm 3.4.1).
#[derive(Debug, Clone)]
pub(crate) struct Lu {
    n: usize,
    a: Vec<f64>,
    pivots: Vec<usize>,
}

/// The matrix has a zero (or non-finite) pivot: it is singular to working precision.
#[derive(Debug, Clone, Copy, PartialEq)]
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

    /// The matrix to fill (row-major) before [`Lu::factor`].
    pub(crate) fn matrix_mut(&mut self) -> &mut [f64] {
        &mut self.a
    }

    /// Factors the matrix in place.
    pub(crate) fn factor(&mut self) -> Result<(), Singular> {
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
            let pivot = self.a[k * n + k];
            for i in k + 1..n {
                let m = self.a[i * n + k] / pivot;
                self.a[i * n + k] = m;
                if m != 0.0 {
                    for j in k + 1..n {
                        self.a[i * n + j] -= m * self.a[k * n + j];
                    }
                }
            }
        }
        Ok(())
    }

    /// Solves `A·x = b` with the factors, `b` overwritten by `x`.
    #[allow(clippy::needless_range_loop)] // index notation mirrors the algorithm
    pub(crate) fn solve(&self, b: &mut [f64]) {
        let n = self.n;
        for k in 0..n {
            b.swap(k, self.pivots[k]);
        }
        for i in 0..n {
            let mut s = b[i];
            for j in 0..i {
                s -= self.a[i * n + j] * b[j];
            }
            b[i] = s;
        }
        for i in (0..n).rev() {
            let mut s = b[i];
            for j in i + 1..n {
                s -= self.a[i * n + j] * b[j];
            }
            b[i] = s / self.a[i * n + i];
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

    #[test]
    fn reports_a_singular_matrix() {
        let mut lu = Lu::new(2);
        lu.matrix_mut().copy_from_slice(&[1.0, 2.0, 2.0, 4.0]);
        assert_eq!(lu.factor(), Err(Singular));
    }
}
