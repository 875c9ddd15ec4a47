//! What an exported plant runs: a scenario's step-wise run
//! ([`rover_scenario::Stepper`]), behind a trait so that one FMU
//! or C library serves any plant: the built-in rovers' generated plants and
//! the generic plant of a rover file ([`builtin`]), or a plant derived in
//! Rust source (the crate's documentation says how).

use rover_dynamics::plant::Plant;
use rover_runtime::row::Columns;
use rover_runtime::sim::{CommandError, RunError};
use rover_scenario::Stepper;
use rover_scenario::prepare::{PrepareError, Prepared};

/// A scenario's run, advanced by the caller (an FMU's importer, a C
/// program). Every method but the constructor's allocates nothing.
pub trait Run: Send {
    /// Back to t = 0 (the scenario's initial state and commands).
    fn reset(&mut self);
    /// Advance to `until` \[s\] ([`Stepper::advance_to`]).
    fn advance_to(&mut self, until: f64) -> Result<(), RunError>;
    /// Time \[s\].
    fn time(&self) -> f64;
    /// The scenario's output interval \[s\].
    fn output_step(&self) -> f64;
    /// The row's columns.
    fn columns(&self) -> &Columns;
    /// The row at the current time (one value per column).
    fn row_into(&self, out: &mut [f64]);
    /// Open-loop motor torques [N·m] and steering angles \[rad\] per
    /// wheel, added to the scenario's own loops.
    fn set_commands(&mut self, torques: &[f64], steering: &[f64]) -> Result<(), CommandError>;
    /// Spring `coord`'s neutral (0-based) \[rad or m\].
    fn set_neutral(&mut self, coord: usize, neutral: f64);
    /// The run's error, once it has failed.
    fn failure(&self) -> Option<&RunError>;
}

impl<P: Plant + Clone + Send> Run for Stepper<P> {
    fn reset(&mut self) {
        Stepper::reset(self);
    }
    fn advance_to(&mut self, until: f64) -> Result<(), RunError> {
        Stepper::advance_to(self, until)
    }
    fn time(&self) -> f64 {
        Stepper::time(self)
    }
    fn output_step(&self) -> f64 {
        self.dt()
    }
    fn columns(&self) -> &Columns {
        Stepper::columns(self)
    }
    fn row_into(&self, out: &mut [f64]) {
        Stepper::row_into(self, out);
    }
    fn set_commands(&mut self, torques: &[f64], steering: &[f64]) -> Result<(), CommandError> {
        self.command_buffer().copy_from_slice(torques);
        self.apply_torques()?;
        self.command_buffer().copy_from_slice(steering);
        self.apply_steering()
    }
    fn set_neutral(&mut self, coord: usize, neutral: f64) {
        Stepper::set_neutral(self, coord, neutral);
    }
    fn failure(&self) -> Option<&RunError> {
        Stepper::failure(self)
    }
}

/// Builds the run of a prepared scenario: the plant is the factory's
/// choice.
pub type Factory = fn(&Prepared) -> Result<Box<dyn Run>, PrepareError>;

/// The plant `rover simulate` runs: a built-in rover's generated plant,
/// the generic plant of a rover file ([`Prepared::stepper`]).
pub fn builtin(prepared: &Prepared) -> Result<Box<dyn Run>, PrepareError> {
    Ok(Box::new(prepared.stepper(false)?))
}
