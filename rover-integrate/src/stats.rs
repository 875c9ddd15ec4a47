//! Work counters of an integrator.

use serde::Serialize;

/// What an integrator has done since it was built: the cost of a run, for summaries and
/// for comparing methods. Counters only grow; [`restart`](super::Integrator::restart) keeps them.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize)]
pub struct Stats {
    /// Accepted steps.
    pub steps: u64,
    /// Rejected step attempts: error test failed, Newton iteration did not converge, or the
    /// candidate state was not finite.
    pub rejected_steps: u64,
    /// Right-hand-side evaluations, including those spent on finite-difference Jacobians, on
    /// the starting step size and (semi-implicit Euler) on position rates.
    pub rhs_evals: u64,
    /// Jacobian evaluations (exact or by finite differences).
    pub jacobian_evals: u64,
    /// LU factorizations of the Newton iteration matrix `I − c·J`.
    pub lu_decompositions: u64,
}
