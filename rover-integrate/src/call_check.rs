//! Checks every `advance` call makes before it steps.

use super::{IntegrateError, OdeSystem};

/// Validates the arguments of an `advance` call for an integrator of dimension `dim`.
/// Returns `Ok(true)` when there is nothing to do (`t_target == t`).
pub(crate) fn check_call<S: OdeSystem + ?Sized>(
    dim: usize,
    sys: &S,
    t: f64,
    y: &[f64],
    t_target: f64,
) -> Result<bool, IntegrateError<S::Error>> {
    if sys.dim() != dim || y.len() != dim {
        return Err(IntegrateError::DimensionMismatch {
            integrator: dim,
            system: sys.dim(),
            state: y.len(),
        });
    }
    if !t.is_finite() || !t_target.is_finite() || t_target < t {
        return Err(IntegrateError::BadTarget { t, t_target });
    }
    check_finite(t, y)?;
    Ok(t_target == t)
}

/// `Err(NonFinite)` naming the first NaN or infinite component of `y` at time `t`.
pub(crate) fn check_finite<E>(t: f64, y: &[f64]) -> Result<(), IntegrateError<E>> {
    match first_non_finite(y) {
        Some(component) => Err(IntegrateError::NonFinite {
            t,
            component,
            value: y[component],
        }),
        None => Ok(()),
    }
}

/// Index of the first NaN or infinite entry.
pub(crate) fn first_non_finite(y: &[f64]) -> Option<usize> {
    y.iter().position(|v| !v.is_finite())
}
