//! Polynomial fits of one coordinate's share of a point's motion
//! (MODEL.md §3, paper eq. 32–33), and their maximum error over the range.
//!
//! Outputs are `[Δu_x, Δu_y, Δu_z, θ]`, zero at the rest value y_c; the
//! fits keep that: the polynomial is `Σ_{p=1}^{k−1} c_p·ξ^p`, ξ = y − y_c,
//! so the rest geometry is exact and member angles vanish at rest.

use crate::jet::{Jet, MAX_TERMS};
use crate::linkage::{CoordRange, FitMethod, FitOptions};

/// Samples checked for assembly before fitting.
const ASSEMBLY_SAMPLES: usize = 1000;
/// Uniform samples of the error before refining its local maxima.
const ERROR_SAMPLES: usize = 400;
/// Golden-section steps per local maximum (bracket shrinks by 0.618 each).
const REFINE_STEPS: usize = 40;

/// Why a share cannot be fitted.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum FitFailure {
    /// The linkage does not assemble at this coordinate value (the one
    /// nearest the rest value among the failing samples).
    CannotAssemble {
        /// The coordinate value.
        at: f64,
    },
}

/// A fitted share: coefficients of ξ⁰ … ξ^(k−1) (the first is 0) for each
/// of the four outputs, and the largest errors over the range.
#[derive(Clone, Debug, PartialEq)]
pub struct ShareFit {
    /// `coeffs[p] = [Δu_x, Δu_y, Δu_z, θ]` coefficient of ξ^p.
    pub coeffs: Vec<[f64; 4]>,
    /// Largest |Δu_fit − Δu_exact| (Euclidean) \[m\].
    pub position_error: f64,
    /// Where it occurs.
    pub position_error_at: f64,
    /// Largest |θ_fit − θ_exact| \[rad\].
    pub angle_error: f64,
    /// Where it occurs.
    pub angle_error_at: f64,
}

/// Value of `Σ_p c_p·ξ^p` for each output.
pub fn eval_share(coeffs: &[[f64; 4]], xi: f64) -> [f64; 4] {
    let mut v = [0.0; 4];
    for c in coeffs.iter().rev() {
        for k in 0..4 {
            v[k] = v[k] * xi + c[k];
        }
    }
    v
}

/// Fit a share. `exact` gives the outputs at a value, `series` their Taylor
/// series about a value (the same kinematics evaluated on a [`Jet`]).
pub fn fit_share(
    exact: &dyn Fn(f64) -> Option<[f64; 4]>,
    series: &dyn Fn(Jet) -> Option<[Jet; 4]>,
    range: CoordRange,
    options: &FitOptions,
) -> Result<ShareFit, FitFailure> {
    // Report the failing value nearest the rest value: where the linkage
    // stops assembling.
    let mut failure: Option<f64> = None;
    for i in 0..=ASSEMBLY_SAMPLES {
        let y = range.min + (range.max - range.min) * i as f64 / ASSEMBLY_SAMPLES as f64;
        let assembles = exact(y).is_some_and(|v| v.iter().all(|x| x.is_finite()));
        if !assembles && failure.is_none_or(|f| (y - range.rest).abs() < (f - range.rest).abs()) {
            failure = Some(y);
        }
    }
    if let Some(at) = failure {
        return Err(FitFailure::CannotAssemble { at });
    }
    let terms = options.terms.clamp(2, MAX_TERMS);
    let coeffs = match options.method {
        FitMethod::Taylor => {
            let s = series(Jet::variable(range.rest))
                .ok_or(FitFailure::CannotAssemble { at: range.rest })?;
            let mut c = vec![[0.0; 4]; terms];
            for (p, cp) in c.iter_mut().enumerate().skip(1) {
                for k in 0..4 {
                    cp[k] = s[k].c[p];
                }
            }
            c
        }
        FitMethod::LeastSquares => least_squares(exact, range, terms)?,
    };
    let (position_error, position_error_at) = max_error(range, &|y| {
        let e = error_at(exact, &coeffs, range.rest, y);
        (e[0] * e[0] + e[1] * e[1] + e[2] * e[2]).sqrt()
    });
    let (angle_error, angle_error_at) =
        max_error(range, &|y| error_at(exact, &coeffs, range.rest, y)[3].abs());
    Ok(ShareFit {
        coeffs,
        position_error,
        position_error_at,
        angle_error,
        angle_error_at,
    })
}

/// Fit minus exact at y (infinite where the linkage does not assemble).
fn error_at(
    exact: &dyn Fn(f64) -> Option<[f64; 4]>,
    coeffs: &[[f64; 4]],
    rest: f64,
    y: f64,
) -> [f64; 4] {
    let fit = eval_share(coeffs, y - rest);
    match exact(y) {
        Some(e) => [fit[0] - e[0], fit[1] - e[1], fit[2] - e[2], fit[3] - e[3]],
        None => [f64::INFINITY; 4],
    }
}

/// Least squares through the rest point: unknowns c_1 … c_(k−1) in the
/// scaled variable t = ξ/s (s the larger half-range), on Chebyshev nodes of
/// the range, solved by Householder QR (no normal equations).
fn least_squares(
    exact: &dyn Fn(f64) -> Option<[f64; 4]>,
    range: CoordRange,
    terms: usize,
) -> Result<Vec<[f64; 4]>, FitFailure> {
    let n = terms - 1;
    let m = (8 * terms).max(64);
    let scale = (range.rest - range.min).max(range.max - range.rest);
    let (mid, half) = (0.5 * (range.min + range.max), 0.5 * (range.max - range.min));
    let mut a = vec![vec![0.0; n]; m];
    let mut b = vec![[0.0; 4]; m];
    for i in 0..m {
        let y = mid + half * (std::f64::consts::PI * (i as f64 + 0.5) / m as f64).cos();
        let t = (y - range.rest) / scale;
        let mut tp = 1.0;
        for col in a[i].iter_mut() {
            tp *= t;
            *col = tp;
        }
        b[i] = exact(y).ok_or(FitFailure::CannotAssemble { at: y })?;
    }
    let x = qr_solve(&mut a, &mut b, n);
    let mut coeffs = vec![[0.0; 4]; terms];
    for p in 1..terms {
        let sp = scale.powi(p as i32);
        for k in 0..4 {
            coeffs[p][k] = x[p - 1][k] / sp;
        }
    }
    Ok(coeffs)
}

/// Solve min ‖A·x − b‖ for four right-hand sides by Householder QR.
/// `a` is m×n with m ≥ n; both are overwritten.
#[allow(clippy::needless_range_loop)]
fn qr_solve(a: &mut [Vec<f64>], b: &mut [[f64; 4]], n: usize) -> Vec<[f64; 4]> {
    let m = a.len();
    for j in 0..n {
        let norm = (j..m).map(|i| a[i][j] * a[i][j]).sum::<f64>().sqrt();
        if norm == 0.0 {
            continue;
        }
        let alpha = if a[j][j] > 0.0 { -norm } else { norm };
        let mut v: Vec<f64> = (j..m).map(|i| a[i][j]).collect();
        v[0] -= alpha;
        let vv: f64 = v.iter().map(|x| x * x).sum();
        if vv == 0.0 {
            continue;
        }
        for col in j..n {
            let d: f64 = (j..m).map(|i| v[i - j] * a[i][col]).sum::<f64>() * 2.0 / vv;
            for i in j..m {
                a[i][col] -= d * v[i - j];
            }
        }
        for k in 0..4 {
            let d: f64 = (j..m).map(|i| v[i - j] * b[i][k]).sum::<f64>() * 2.0 / vv;
            for i in j..m {
                b[i][k] -= d * v[i - j];
            }
        }
    }
    let mut x = vec![[0.0; 4]; n];
    for j in (0..n).rev() {
        for k in 0..4 {
            let mut s = b[j][k];
            for col in j + 1..n {
                s -= a[j][col] * x[col][k];
            }
            x[j][k] = if a[j][j] != 0.0 { s / a[j][j] } else { 0.0 };
        }
    }
    x
}

/// Largest value of a non-negative error over the range and where: uniform
/// samples, then a golden-section search around every sampled local maximum.
pub fn max_error(range: CoordRange, error: &dyn Fn(f64) -> f64) -> (f64, f64) {
    let h = (range.max - range.min) / ERROR_SAMPLES as f64;
    let ys: Vec<f64> = (0..=ERROR_SAMPLES)
        .map(|i| range.min + h * i as f64)
        .collect();
    let es: Vec<f64> = ys.iter().map(|&y| error(y)).collect();
    let mut best = (es[0], ys[0]);
    for i in 0..es.len() {
        let left = if i > 0 { es[i - 1] } else { f64::NEG_INFINITY };
        let right = if i + 1 < es.len() {
            es[i + 1]
        } else {
            f64::NEG_INFINITY
        };
        if es[i] > best.0 || es[i].is_nan() {
            best = (es[i], ys[i]);
        }
        if es[i] >= left && es[i] >= right {
            let lo = (ys[i] - h).max(range.min);
            let hi = (ys[i] + h).min(range.max);
            let (e, y) = golden_max(lo, hi, error);
            if e > best.0 {
                best = (e, y);
            }
        }
    }
    best
}

/// Golden-section search for the maximum of `f` on [lo, hi].
fn golden_max(mut lo: f64, mut hi: f64, f: &dyn Fn(f64) -> f64) -> (f64, f64) {
    const R: f64 = 0.618_033_988_749_894_8;
    let mut x1 = hi - R * (hi - lo);
    let mut x2 = lo + R * (hi - lo);
    let (mut f1, mut f2) = (f(x1), f(x2));
    for _ in 0..REFINE_STEPS {
        if f1 < f2 {
            lo = x1;
            x1 = x2;
            f1 = f2;
            x2 = lo + R * (hi - lo);
            f2 = f(x2);
        } else {
            hi = x2;
            x2 = x1;
            f2 = f1;
            x1 = hi - R * (hi - lo);
            f1 = f(x1);
        }
    }
    if f1 > f2 { (f1, x1) } else { (f2, x2) }
}
