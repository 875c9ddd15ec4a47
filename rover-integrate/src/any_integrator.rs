//! One of the integrators, chosen at run time from a scenario file.

use super::{
    Bdf, Dopri5, IntegrateError, Integrator, OdeSystem, Rk4, Ros2, SemiImplicitEuler, Stats,
};

/// One of the integration methods, as built by
/// [`IntegratorConfig::build`](super::IntegratorConfig::build); forwards to the method.
#[derive(Debug, Clone)]
pub enum AnyIntegrator {
    /// Fixed-step RK4.
    Rk4(Rk4),
    /// Fixed-step semi-implicit Euler.
    SemiImplicitEuler(SemiImplicitEuler),
    /// Adaptive Dormand–Prince 5(4) (boxed: its workspace handles are larger).
    Dopri5(Box<Dopri5>),
    /// Variable-order NDF/BDF (boxed: its workspace handles are larger).
    Bdf(Box<Bdf>),
    /// Fixed-step Rosenbrock ROS2 (boxed, as BDF).
    Ros2(Box<Ros2>),
}

impl Integrator for AnyIntegrator {
    fn advance<S: OdeSystem + ?Sized>(
        &mut self,
        sys: &mut S,
        t: &mut f64,
        y: &mut [f64],
        t_target: f64,
    ) -> Result<(), IntegrateError<S::Error>> {
        match self {
            Self::Rk4(m) => m.advance(sys, t, y, t_target),
            Self::SemiImplicitEuler(m) => m.advance(sys, t, y, t_target),
            Self::Dopri5(m) => m.advance(sys, t, y, t_target),
            Self::Bdf(m) => m.advance(sys, t, y, t_target),
            Self::Ros2(m) => m.advance(sys, t, y, t_target),
        }
    }

    fn advance_output<S: OdeSystem + ?Sized>(
        &mut self,
        sys: &mut S,
        t: &mut f64,
        y: &mut [f64],
        t_target: f64,
        t_limit: f64,
    ) -> Result<(), IntegrateError<S::Error>> {
        match self {
            Self::Bdf(m) => m.advance_output(sys, t, y, t_target, t_limit),
            _ => self.advance(sys, t, y, t_target),
        }
    }

    fn restart(&mut self) {
        match self {
            Self::Rk4(m) => m.restart(),
            Self::SemiImplicitEuler(m) => m.restart(),
            Self::Dopri5(m) => m.restart(),
            Self::Bdf(m) => m.restart(),
            Self::Ros2(m) => m.restart(),
        }
    }

    fn stats(&self) -> Stats {
        match self {
            Self::Rk4(m) => m.stats(),
            Self::SemiImplicitEuler(m) => m.stats(),
            Self::Dopri5(m) => m.stats(),
            Self::Bdf(m) => m.stats(),
            Self::Ros2(m) => m.stats(),
        }
    }

    fn dim(&self) -> usize {
        match self {
            Self::Rk4(m) => m.dim(),
            Self::SemiImplicitEuler(m) => m.dim(),
            Self::Dopri5(m) => m.dim(),
            Self::Bdf(m) => m.dim(),
            Self::Ros2(m) => m.dim(),
        }
    }

    fn name(&self) -> &'static str {
        match self {
            Self::Rk4(m) => m.name(),
            Self::SemiImplicitEuler(m) => m.name(),
            Self::Dopri5(m) => m.name(),
            Self::Bdf(m) => m.name(),
            Self::Ros2(m) => m.name(),
        }
    }
}
