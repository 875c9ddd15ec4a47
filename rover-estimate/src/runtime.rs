//! The rover runtime's system as the filter's process model (the
//! `runtime` feature): the plant, the ground and a controller without
//! loops, built by [`RoverSystem::open_loop`], whose state is the
//! process model's `y = [x; w; ω]`.
//!
//! The Jacobian is the runtime's assembled one (the generated plant's
//! exact Jacobian, chained with the wheels' load derivatives,
//! [`RoverSystem::rhs_and_jacobian`]); a plant without an exact Jacobian
//! (the generic plant) falls back to forward differences of the whole
//! right-hand side, as the runtime's integrators do.

use core::fmt;
use core::ops::Range;

use rover_dynamics::HeightField;
use rover_dynamics::plant::Plant;
use rover_runtime::integrate::OdeSystem;
use rover_runtime::sim::{CommandError, RoverSystem, SimError};

use crate::ProcessModel;

/// Why the runtime's system failed as a process model.
#[derive(Clone, Debug, PartialEq)]
pub enum RuntimeError {
    /// A command was refused (its count, a non-finite value, a wheel that
    /// does not steer).
    Command(CommandError),
    /// An evaluation failed (a wheel off the map, a singular attitude).
    Evaluation(SimError),
}

impl fmt::Display for RuntimeError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            RuntimeError::Command(e) => write!(f, "{e}"),
            RuntimeError::Evaluation(e) => write!(f, "{e}"),
        }
    }
}

impl core::error::Error for RuntimeError {}

impl<P: Plant, H: HeightField> ProcessModel for RoverSystem<P, H> {
    type Error = RuntimeError;

    fn dof(&self) -> usize {
        RoverSystem::dof(self)
    }

    fn dim(&self) -> usize {
        OdeSystem::dim(self)
    }

    fn wheel_count(&self) -> usize {
        self.plant.wheel_count()
    }

    fn spin_range(&self) -> Range<usize> {
        RoverSystem::spin_range(self)
    }

    /// The description's gravity for a system built by
    /// [`RoverSystem::open_loop`]; NaN otherwise, which the estimator
    /// refuses (such a system also carries its loops' integral states).
    fn gravity(&self) -> f64 {
        RoverSystem::gravity(self).unwrap_or(f64::NAN)
    }

    fn set_inputs(&mut self, torques: &[f64], steering: &[f64]) -> Result<(), RuntimeError> {
        self.set_torques(torques).map_err(RuntimeError::Command)?;
        self.set_steering(steering).map_err(RuntimeError::Command)
    }

    fn rhs(&mut self, t: f64, y: &[f64], dy: &mut [f64]) -> Result<(), RuntimeError> {
        OdeSystem::rhs(self, t, y, dy).map_err(RuntimeError::Evaluation)
    }

    fn rhs_and_jacobian(
        &mut self,
        t: f64,
        y: &[f64],
        dy: &mut [f64],
        jac: &mut [f64],
    ) -> Result<(), RuntimeError> {
        RoverSystem::rhs_and_jacobian(self, t, y, dy, jac).map_err(RuntimeError::Evaluation)
    }

    fn wheel_rates(
        &mut self,
        t: f64,
        y: &[f64],
        rates: &mut [f64],
        gradient: &mut [f64],
    ) -> Result<(), RuntimeError> {
        self.wheel_spin_rate_gradients(t, y, rates, gradient);
        Ok(())
    }

    fn wheel_outputs(&self, normal: &mut [f64], slip: &mut [f64]) {
        for ((n, s), r) in normal.iter_mut().zip(slip.iter_mut()).zip(self.reports()) {
            *n = r.normal;
            *s = r.slip;
        }
    }
}
