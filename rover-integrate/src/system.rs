//! The system of ordinary differential equations an integrator advances.

/// A first-order system `ẏ = f(t, y)` whose dimension is known at run time.
///
/// For a rover, `y = [x; w]`: `n` positions `x` (X, Y, Z, φ, θ, ψ, y1..ym) followed by `n`
/// pseudo-velocities `w`, with `ẋ = B(x)·w` and `ẇ = a(x, w)` (MODEL.md §2–§5). The integrators
/// call [`rhs`](OdeSystem::rhs) with slices of length [`dim`](OdeSystem::dim) and never allocate
/// on the system's behalf.
///
/// Controls are held constant between two calls of `advance` (zero-order hold): a system whose
/// right-hand side changes between calls (a new controller sample) should be followed by
/// `Integrator::restart`, so multistep history is not carried across the jump.
pub trait OdeSystem {
    /// Why the right-hand side can fail (singular mass matrix, wheel off the terrain map, …).
    /// The integrators return it wrapped with the time of the failing evaluation.
    type Error;

    /// Dimension of the state `y`.
    fn dim(&self) -> usize;

    /// Writes `dy = f(t, y)`. Both slices have length [`dim`](OdeSystem::dim).
    fn rhs(&mut self, t: f64, y: &[f64], dy: &mut [f64]) -> Result<(), Self::Error>;

    /// Number of leading position entries `x` in `y = [x; w]`, used by semi-implicit Euler.
    /// Default: half the dimension.
    fn split(&self) -> usize {
        self.dim() / 2
    }

    /// The position rates `ẋ` (length [`split`](OdeSystem::split)) for the positions and
    /// velocities in `y` (length [`dim`](OdeSystem::dim)), for semi-implicit Euler: for the
    /// rover, `ẋ = B(x)·w` without the cost of `ẇ`. Default: `None`, and the integrator takes
    /// the leading entries of a full [`rhs`](OdeSystem::rhs) evaluation instead.
    fn position_rates(
        &mut self,
        _t: f64,
        _y: &[f64],
        _dx: &mut [f64],
    ) -> Option<Result<(), Self::Error>> {
        None
    }

    /// Called after every step the integrator accepts and builds on, with
    /// the state it reached, in increasing time: no later evaluation is
    /// at an earlier time (BDF's landings on an output instant, from which
    /// the next step does not start, are not reported). A system with
    /// memory (the ground's ruts, which the wheels deepen as they go)
    /// updates it here; whatever it changes must lie where the right-hand
    /// side does not read it from the present state on, so that the step
    /// just taken, and a multistep method's history, stay valid. Default:
    /// nothing.
    fn step_accepted(&mut self, _t: f64, _y: &[f64]) {}

    /// Each component's error scale, in its own units (m, rad, m/s, …): the magnitude below
    /// which its error counts in absolute rather than relative terms, and whether its size
    /// counts at all. An adaptive method whose configuration gives no `atol` controls component
    /// `i`'s local error to `rtol·(scale_i + relative_i·|y_i|)`, so that one `rtol` means the
    /// same for a length and an angular rate, and a tighter `rtol` tightens every component.
    /// `relative_i` is 1 for most components; 0 for one whose size means nothing (a position
    /// or a heading, which the dynamics does not depend on: 1e-3 of a position 1 km from the
    /// origin would be a metre). Fills `scale` (positive finite entries) and `relative` (each
    /// in [0, 1]), both of length [`dim`](OdeSystem::dim), and returns true; default: false,
    /// and the method uses a uniform `atol` instead (see the method's configuration).
    fn error_scale(&self, _scale: &mut [f64], _relative: &mut [f64]) -> bool {
        false
    }

    /// The system's own Jacobian `∂f/∂y` at `(t, y)`, row-major (`jac[i·dim + j] =
    /// ∂f_i/∂y_j`), for the implicit methods (BDF, ROS2), with the number of right-hand-side
    /// evaluations it spent. It may approximate: the methods need it for convergence and
    /// stability, not for their order. Default: `None`, and the integrator uses forward finite
    /// differences (`dim` extra right-hand-side evaluations).
    fn jacobian(
        &mut self,
        _t: f64,
        _y: &[f64],
        _jac: &mut [f64],
    ) -> Option<Result<usize, Self::Error>> {
        None
    }
}
