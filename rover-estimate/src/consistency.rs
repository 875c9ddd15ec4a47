//! How well an estimate agrees with the truth, when the truth is known (a
//! simulated run): root-mean-square errors, and the filter's consistency,
//! the normalized estimation error squared (NEES) `εᵀ·P⁻¹·ε` of each
//! sample against its χ² interval (Bar-Shalom, Li and Kirubarajan,
//! *Estimation with Applications to Tracking and Navigation*, Wiley 2001,
//! §5.4.2): a filter whose covariance is honest has the NEES of an
//! n-dimensional error inside the two-sided 95 % interval of χ²(n) at
//! 95 % of the samples.

/// The standard normal's 97.5 % quantile: the two-sided 95 % interval's
/// half-width in standard deviations.
const Z_975: f64 = 1.959_963_984_540_054;

/// The two-sided 95 % interval of the χ² distribution with `dof` degrees
/// of freedom, `[χ²₀.₀₂₅, χ²₀.₉₇₅]`, by the Wilson–Hilferty cube-root
/// normal approximation (Wilson and Hilferty, PNAS 17, 1931): the upper
/// bound within 0.1 % of the exact quantile from 5 degrees of freedom on,
/// the lower within 0.2 % from 20 on (a rover's error has 2N ≥ 20
/// entries), 0.75 % at 10 and 4 % at 5.
pub fn chi2_interval_95(dof: usize) -> (f64, f64) {
    let k = dof as f64;
    let s = libm::sqrt(2.0 / (9.0 * k));
    let q = |z: f64| {
        let c = 1.0 - 2.0 / (9.0 * k) + z * s;
        k * c * c * c
    };
    (q(-Z_975), q(Z_975))
}

/// Running root-mean-square of one error.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Rms {
    sum: f64,
    count: usize,
}

impl Rms {
    /// Adds one error.
    pub fn add(&mut self, error: f64) {
        self.sum += error * error;
        self.count += 1;
    }
    /// The root mean square so far (0 before any error).
    pub fn value(&self) -> f64 {
        if self.count == 0 {
            0.0
        } else {
            libm::sqrt(self.sum / self.count as f64)
        }
    }
    /// How many errors were added.
    pub fn count(&self) -> usize {
        self.count
    }
}

/// How many samples' NEES fell inside the 95 % interval of χ²(dof).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct NeesTally {
    bounds: (f64, f64),
    inside: usize,
    below: usize,
    above: usize,
    sum: f64,
}

impl NeesTally {
    /// A tally for errors of `dof` entries.
    pub fn new(dof: usize) -> Self {
        Self {
            bounds: chi2_interval_95(dof),
            inside: 0,
            below: 0,
            above: 0,
            sum: 0.0,
        }
    }
    /// Adds one sample's NEES.
    pub fn add(&mut self, nees: f64) {
        self.sum += nees;
        if nees < self.bounds.0 {
            self.below += 1;
        } else if nees > self.bounds.1 {
            self.above += 1;
        } else {
            self.inside += 1;
        }
    }
    /// The interval `[χ²₀.₀₂₅, χ²₀.₉₇₅]`.
    pub fn bounds(&self) -> (f64, f64) {
        self.bounds
    }
    /// The fraction of samples inside the interval (0 before any).
    pub fn fraction_inside(&self) -> f64 {
        let n = self.count();
        if n == 0 {
            0.0
        } else {
            self.inside as f64 / n as f64
        }
    }
    /// Samples below the interval (a covariance too large: a timid
    /// filter) and above it (too small: an overconfident one).
    pub fn outside(&self) -> (usize, usize) {
        (self.below, self.above)
    }
    /// The mean NEES, which a consistent filter keeps near `dof`.
    pub fn mean(&self) -> f64 {
        let n = self.count();
        if n == 0 { 0.0 } else { self.sum / n as f64 }
    }
    /// Samples added.
    pub fn count(&self) -> usize {
        self.inside + self.below + self.above
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn chi2_interval_matches_the_tables() {
        // Exact quantiles (e.g. NIST/SEMATECH e-Handbook, Table 1.3.6.7.4).
        let table = [
            (5, 0.831, 12.833, 0.041),
            (10, 3.247, 20.483, 0.0076),
            (20, 9.591, 34.170, 0.002),
            (30, 16.791, 46.979, 0.002),
        ];
        for (dof, lo, hi, lower_tolerance) in table {
            let (l, h) = chi2_interval_95(dof);
            assert!((l - lo).abs() < lower_tolerance * lo, "{dof}: {l} vs {lo}");
            assert!((h - hi).abs() < 1e-3 * hi, "{dof}: {h} vs {hi}");
        }
    }

    #[test]
    fn tally_counts_each_side() {
        let mut t = NeesTally::new(20);
        for v in [1.0, 20.0, 21.0, 50.0] {
            t.add(v);
        }
        assert_eq!(t.outside(), (1, 1));
        assert_eq!(t.fraction_inside(), 0.5);
        assert_eq!(t.mean(), 23.0);
        let mut r = Rms::default();
        r.add(3.0);
        r.add(-4.0);
        assert!((r.value() - 12.5f64.sqrt()).abs() < 1e-15);
    }
}
