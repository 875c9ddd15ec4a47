//! The Jacobian `∂f/∂y` for implicit methods: the system's own, or forward differences.

use serde::{Deserialize, Serialize};

use super::{IntegrateError, OdeSystem, Stats};

/// Where an implicit method takes its Jacobian from (`jacobian = "system"` in
/// `[integrator.bdf]` or `[integrator.ros2]`).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum JacobianSource {
    /// The system's own ([`OdeSystem::jacobian`]: for a rover with a generated plant,
    /// assembled from the plant's exact Jacobian and the wheels' load derivatives), and
    /// forward differences where it has none. The default.
    #[default]
    System,
    /// Forward differences of the right-hand side, `dim` evaluations each time.
    Differences,
}

/// Scratch for [`jacobian`]: a perturbed state and its derivative, allocated once.
#[derive(Debug, Clone)]
pub(crate) struct JacobianScratch {
    y: Vec<f64>,
    f: Vec<f64>,
    source: JacobianSource,
}

impl JacobianScratch {
    pub(crate) fn new(dim: usize, source: JacobianSource) -> Self {
        Self {
            y: vec![0.0; dim],
            f: vec![0.0; dim],
            source,
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
    if scratch.source == JacobianSource::System
        && let Some(result) = sys.jacobian(t, y, jac)
    {
        stats.rhs_evals += result.map_err(rhs_error)? as u64;
        return Ok(());
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
