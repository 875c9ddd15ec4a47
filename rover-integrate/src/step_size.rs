//! Step-size logic shared by the adaptive methods: the starting step, landing on the target
//! and the step-size controllers.

use super::call_check::check_finite;
use super::norm::{Atol, scaled_norm};
use super::{IntegrateError, OdeSystem, Stats};

/// Relative slack under which the rest of the interval is taken in one (slightly longer)
/// step instead of leaving a sliver of roundoff size for one more step.
const LANDING_SLACK: f64 = 1e-6;

/// The step to take from `t` towards `t_target` when the method would like `h`, and whether
/// it lands on the target. A landing step ends exactly at `t_target` (the caller sets the new
/// time to `t_target`, not `t + h`, so no roundoff accumulates across calls).
pub(crate) fn clamp_to_target(t: f64, h: f64, t_target: f64) -> (f64, bool) {
    let remaining = t_target - t;
    if h * (1.0 + LANDING_SLACK) >= remaining {
        (remaining, true)
    } else {
        (h, false)
    }
}

/// Fixed steps of `step` from `*t` to `t_target`, the last one shortened to
/// land exactly on it (see [`clamp_to_target`]): `one(t, h, y)` takes one
/// step of `h` from `(t, y)` in place. A non-finite state stops the loop
/// with the time it was reached at. The loop of every fixed-step method.
pub(crate) fn fixed_steps<E>(
    step: f64,
    t: &mut f64,
    y: &mut [f64],
    t_target: f64,
    mut one: impl FnMut(f64, f64, &mut [f64]) -> Result<(), IntegrateError<E>>,
) -> Result<(), IntegrateError<E>> {
    while *t < t_target {
        let (h, lands) = clamp_to_target(*t, step, t_target);
        one(*t, h, y)?;
        *t = if lands { t_target } else { *t + h };
        check_finite(*t, y)?;
    }
    Ok(())
}

/// Tolerances and limits the starting-step heuristic needs.
pub(crate) struct StartingStep<'a> {
    /// Relative tolerance.
    pub rtol: f64,
    /// Absolute tolerances.
    pub atol: Atol<'a>,
    /// Order `q` of the local error estimate (the error behaves like `h^(q+1)`).
    pub order: u32,
    /// Largest step allowed \[s\].
    pub max_step: f64,
}

/// Starting step size (Hairer, Nørsett & Wanner I, §II.4, p. 169):
/// ```text
/// d0 = ‖y0‖, d1 = ‖f(t0, y0)‖, h0 = 0.01·d0/d1 (1e-6 if either is below 1e-5)
/// y1 = y0 + h0·f0, d2 = ‖f(t0 + h0, y1) − f0‖ / h0
/// h1 = (0.01 / max(d1, d2))^(1/(q+1))   (max(1e-6, 1e-3·h0) if max(d1, d2) ≤ 1e-15)
/// h  = min(100·h0, h1, max_step)
/// ```
/// with the weighted norm of the tolerances. Costs one right-hand-side evaluation; `y1` and
/// `f1` are scratch of length `dim`.
#[allow(clippy::too_many_arguments)]
pub(crate) fn starting_step<S: OdeSystem + ?Sized>(
    sys: &mut S,
    t0: f64,
    y0: &[f64],
    f0: &[f64],
    limits: &StartingStep<'_>,
    y1: &mut [f64],
    f1: &mut [f64],
    stats: &mut Stats,
) -> Result<f64, IntegrateError<S::Error>> {
    let StartingStep {
        rtol,
        atol,
        order,
        max_step,
    } = *limits;
    let d0 = scaled_norm(y0, y0, rtol, atol);
    let d1 = scaled_norm(f0, y0, rtol, atol);
    let h0 = if d0 < 1e-5 || d1 < 1e-5 {
        1e-6
    } else {
        0.01 * d0 / d1
    };
    let h0 = h0.min(max_step);
    for ((y1i, y0i), f0i) in y1.iter_mut().zip(y0).zip(f0) {
        *y1i = y0i + h0 * f0i;
    }
    let t1 = t0 + h0;
    sys.rhs(t1, y1, f1)
        .map_err(|source| IntegrateError::Rhs { t: t1, source })?;
    stats.rhs_evals += 1;
    for (f1i, f0i) in f1.iter_mut().zip(f0) {
        *f1i -= f0i;
    }
    let d2 = scaled_norm(f1, y0, rtol, atol) / h0;
    let dmax = d1.max(d2);
    let h1 = if dmax <= 1e-15 || !dmax.is_finite() {
        (h0 * 1e-3).max(1e-6)
    } else {
        (0.01 / dmax).powf(1.0 / f64::from(order + 1))
    };
    Ok((100.0 * h0).min(h1).min(max_step))
}

/// The step to ask for after a step of size `h` was taken while the controller wanted
/// `h_wanted`: when the step was shortened to land on a target, the shortened step says
/// little about the next one, so the earlier wish is kept unless the error now asks for less.
pub(crate) fn next_after_landing(h: f64, h_wanted: f64, factor: f64) -> f64 {
    if h < h_wanted && factor >= 1.0 {
        h_wanted.max(h * factor)
    } else {
        h * factor
    }
}
