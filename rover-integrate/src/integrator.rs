//! The interface every integration method offers.

use super::{IntegrateError, OdeSystem, Stats};

/// An integration method with its workspace (sized once, for one dimension). It does not own
/// the state: the caller keeps `t` and `y` and passes them to each call, so a run can be
/// checkpointed, inspected or modified between calls.
pub trait Integrator {
    /// Advances `(t, y)` to exactly `t_target` (bit for bit: `*t == t_target` on success), the
    /// last step shortened to land on it. On error, `(t, y)` hold the last accepted step.
    ///
    /// Adaptive methods keep their step size (and, if the call starts from exactly the time
    /// and state the previous call ended at, their history) from one call to the next.
    fn advance<S: OdeSystem + ?Sized>(
        &mut self,
        sys: &mut S,
        t: &mut f64,
        y: &mut [f64],
        t_target: f64,
    ) -> Result<(), IntegrateError<S::Error>>;

    /// Advances `(t, y)` to the output instant `t_target` (`*t == t_target` on success), where
    /// nothing changes: a method with an interpolant may step past it, never past `t_limit`
    /// (≥ `t_target`: the next instant where the caller may change the system or restart),
    /// and give the solution there from the interpolant, its history staying on its own steps;
    /// the next call goes on from that history when it starts from exactly the time and state
    /// this one ended at. Default: [`advance`](Integrator::advance) to `t_target`.
    fn advance_output<S: OdeSystem + ?Sized>(
        &mut self,
        sys: &mut S,
        t: &mut f64,
        y: &mut [f64],
        t_target: f64,
        _t_limit: f64,
    ) -> Result<(), IntegrateError<S::Error>> {
        self.advance(sys, t, y, t_target)
    }

    /// Tells the integrator that the right-hand side changed discontinuously (a new control
    /// sample): history from before is dropped, the step size is kept as a first guess.
    /// A changed state is detected without it.
    fn restart(&mut self);

    /// Work done since the integrator was built.
    fn stats(&self) -> Stats;

    /// Dimension the workspace was sized for.
    fn dim(&self) -> usize;

    /// The method's name as written in a scenario file.
    fn name(&self) -> &'static str;
}
