//! The Jacobian `∂f/∂y` for implicit methods: the system's own, or forward differences.

use super::{IntegrateError, OdeSystem, Stats};

/// Scratch for [`jacobian`]: a perturbed state and its derivative, allocated once.
#[derive(Debug, Clone)]
pub(crate) struct JacobianScratch {
    y: Vec<f64>,
    f: Vec<f64>,
}

impl JacobianScratch {
    pub(crate) fn new(dim: usize) -> Self {
        Self {
            y: vec![0.0; dim],
            f: vec![0.0; dim],
        }
    }
}

/// Writes `jac = ∂f/∂y (t, y)` row-major, from [`OdeSystem::jacobian`] when the system has one,
/// otherwise by forward differences with `f0 = f(t, y)` given:
/// ```text
/// J[:, j] = (f(t, y + δ_j·e_j) − f0) / δ_j,   δ_j = √ε · max(|y_j|, 1)
/// ```
/// (Hairer & Wanner II, §IV.8; δ_j rounded so that `y_j + δ_j` is exact). Costs `dim`
/// evaluations, counted in `stats`.
pub(crate) fn jacobian<S: OdeSystem + ?Sized>(
    sys: &mut S,
    t: f64,
    y: &[f64],
    f0: &[f64],
    jac: &mut [f64],
    scratch: &mut JacobianScratch,
    stats: &mut Stats,
) -> Result<(), IntegrateError<S::Error>> {
    let rhs_error = |source| IntegrateError::Rhs { t, source };
    stats.jacobian_evals += 1;
    if let Some(result) = sys.jacobian(t, y, jac) {
        return result.map_err(rhs_error);
    }
    let n = y.len();
    let sqrt_eps = f64::EPSILON.sqrt();
    scratch.y.copy_from_slice(y);
    for j in 0..n {
        let yj = y[j];
        let perturbed = yj + sqrt_eps * yj.abs().max(1.0);
        let delta = perturbed - yj;
        scratch.y[j] = perturbed;
        stats.rhs_evals += 1;
        sys.rhs(t, &scratch.y, &mut scratch.f).map_err(rhs_error)?;
        scratch.y[j] = yj;
        for i in 0..n {
            jac[i * n + j] = (scratch.f[i] - f0[i]) / delta;
        }
    }
    Ok(())
}
