//! Why an integration stopped.

use std::fmt;

/// Why [`Integrator::advance`](super::Integrator::advance) stopped before the target time.
/// Every run-time variant carries the time at which it happened; the state passed to
/// `advance` then holds the last accepted step (at the time `t` left in the caller's variable).
#[derive(Debug, Clone, PartialEq)]
pub enum IntegrateError<E> {
    /// The right-hand side (or Jacobian) returned an error when evaluated at time `t` \[s\].
    Rhs {
        /// Time of the failing evaluation \[s\] (a stage time, not necessarily a step end).
        t: f64,
        /// The system's error.
        source: E,
    },
    /// The step-size controller asked for a step below the configured minimum.
    StepTooSmall {
        /// Time at which the step was to start \[s\].
        t: f64,
        /// The step the controller asked for \[s\].
        h: f64,
        /// The configured minimum \[s\].
        min_step: f64,
    },
    /// The configured number of step attempts per `advance` call was used up.
    TooManySteps {
        /// Time reached \[s\].
        t: f64,
        /// Target of the call \[s\].
        t_target: f64,
        /// The configured limit.
        max_steps: u64,
    },
    /// A state component became NaN or infinite.
    NonFinite {
        /// Time of the offending state \[s\].
        t: f64,
        /// Index of the first non-finite component in `y`.
        component: usize,
        /// Its value (NaN or ±∞).
        value: f64,
    },
    /// The integrator, the system and the state vector disagree on the dimension.
    DimensionMismatch {
        /// Dimension the integrator was built for.
        integrator: usize,
        /// [`OdeSystem::dim`](super::OdeSystem::dim).
        system: usize,
        /// Length of the state slice.
        state: usize,
    },
    /// [`OdeSystem::split`](super::OdeSystem::split) is larger than the dimension.
    BadSplit {
        /// The system's split.
        split: usize,
        /// The system's dimension.
        dim: usize,
    },
    /// The target time is not finite or lies before the current time (integration runs forward).
    BadTarget {
        /// Current time \[s\].
        t: f64,
        /// Requested target \[s\].
        t_target: f64,
    },
}

impl<E> IntegrateError<E> {
    /// The step-size control gave up (a step below the minimum, or the
    /// attempts used up): the solution, or the right-hand side, changes
    /// faster than any step can follow, as at a discontinuity.
    pub fn is_step_control(&self) -> bool {
        matches!(self, Self::StepTooSmall { .. } | Self::TooManySteps { .. })
    }

    /// The simulation time the error refers to, when it has one.
    pub fn time(&self) -> Option<f64> {
        match self {
            Self::Rhs { t, .. }
            | Self::StepTooSmall { t, .. }
            | Self::TooManySteps { t, .. }
            | Self::NonFinite { t, .. }
            | Self::BadTarget { t, .. } => Some(*t),
            Self::DimensionMismatch { .. } | Self::BadSplit { .. } => None,
        }
    }
}

impl<E: fmt::Display> fmt::Display for IntegrateError<E> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Rhs { t, source } => {
                write!(f, "right-hand side failed at t = {t} s: {source}")
            }
            Self::StepTooSmall { t, h, min_step } => write!(
                f,
                "step size {h:e} s at t = {t} s is below the minimum step {min_step:e} s: \
                 the solution changes too fast here (a stiff or chattering contact?); \
                 lower `min_step`, or, with an explicit method, use `[integrator.bdf]`"
            ),
            Self::TooManySteps {
                t,
                t_target,
                max_steps,
            } => write!(
                f,
                "{max_steps} step attempts reached only t = {t} s on the way to {t_target} s: \
                 raise `max_steps`, raise `max_step` if it is set (no step is longer), \
                 or loosen the tolerances; with an explicit method, \
                 `[integrator.bdf]` takes stiff contact in larger steps"
            ),
            Self::NonFinite {
                t,
                component,
                value,
            } => write!(
                f,
                "state component {component} is {value} at t = {t} s: the run diverged"
            ),
            Self::DimensionMismatch {
                integrator,
                system,
                state,
            } => write!(
                f,
                "the integrator was built for dimension {integrator}, but the system has \
                 dimension {system} and the state vector length {state}"
            ),
            Self::BadSplit { split, dim } => write!(
                f,
                "the system declares {split} position entries but has dimension {dim}: \
                 `split` must be at most `dim`"
            ),
            Self::BadTarget { t, t_target } => write!(
                f,
                "target time {t_target} s is not a finite time at or after the current time \
                 {t} s (integration runs forward only)"
            ),
        }
    }
}

impl<E: std::error::Error + 'static> std::error::Error for IntegrateError<E> {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        match self {
            Self::Rhs { source, .. } => Some(source),
            _ => None,
        }
    }
}
