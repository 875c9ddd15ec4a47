//! A whole run: from t = 0 to its end through the [`Driver`], a row at
//! every output instant (and, with sensors, a callback at every sensor
//! instant).

use std::sync::atomic::{AtomicBool, Ordering};

use rover_dynamics::HeightField;
use rover_dynamics::plant::Plant;

use rover_integrate::Integrator;

use super::driver::{Driver, RunOptions};
use super::error::RunError;
use super::system::RoverSystem;

/// One output instant: the state and what the contact and the controller did.
#[derive(Debug)]
pub struct OutputRow<'a, P, H> {
    /// Time \[s\].
    pub t: f64,
    /// The full state `[x; w; ζ]`.
    pub y: &'a [f64],
    /// The system, freshly evaluated at (t, y): wheel states, reports, torques, steering.
    pub system: &'a RoverSystem<P, H>,
}

/// Why the run ended.
#[derive(Clone, Debug, PartialEq)]
pub enum Stop {
    /// The end time was reached.
    Completed,
    /// The user interrupted (Ctrl-C): what was computed is kept.
    Interrupted {
        /// Time reached \[s\].
        t: f64,
    },
    /// The run failed.
    Failed(RunError),
}

/// How a run ended, and its cost.
#[derive(Clone, Debug, PartialEq)]
pub struct RunOutcome {
    /// Why it ended.
    pub stop: Stop,
    /// Time reached \[s\].
    pub t: f64,
    /// Largest |φ| seen at output instants \[rad\].
    pub max_roll: f64,
    /// Largest |θ| seen at output instants \[rad\].
    pub max_pitch: f64,
}

/// Run `sys` from (0, y) to `opts.duration`, calling `output` at t = 0,
/// every `opts.output_step` and at the end. `interrupt` is polled between
/// output instants.
pub fn run<P, H, I, F>(
    sys: &mut RoverSystem<P, H>,
    integ: &mut I,
    y: &mut [f64],
    opts: &RunOptions,
    interrupt: &AtomicBool,
    output: F,
) -> RunOutcome
where
    P: Plant,
    H: HeightField,
    I: Integrator,
    F: FnMut(&OutputRow<'_, P, H>) -> std::io::Result<()>,
{
    let no_sensors = |_: f64, _: &[f64], _: &mut RoverSystem<P, H>| Ok(());
    run_with_sensors(sys, integ, y, opts, None, interrupt, output, no_sensors)
}

/// [`run`] with sensor instants every `sensor_period` seconds from t = 0
/// ([`Driver::with_sensor_period`]; `None`: none, the run of [`run`]):
/// `on_sensor(t, y, sys)` is called at each, t = 0 first, before the
/// output row of the same instant. An error of `on_sensor` (a sensor log
/// that cannot be written, an evaluation that fails) stops the run as
/// failed at that instant.
pub fn run_with_sensors<P, H, I, F, S>(
    sys: &mut RoverSystem<P, H>,
    integ: &mut I,
    y: &mut [f64],
    opts: &RunOptions,
    sensor_period: Option<f64>,
    interrupt: &AtomicBool,
    mut output: F,
    mut on_sensor: S,
) -> RunOutcome
where
    P: Plant,
    H: HeightField,
    I: Integrator,
    F: FnMut(&OutputRow<'_, P, H>) -> std::io::Result<()>,
    S: FnMut(f64, &[f64], &mut RoverSystem<P, H>) -> Result<(), RunError>,
{
    let mut t = 0.0;
    let mut scratch = vec![0.0; y.len()];
    let mut driver = Driver::new(&sys.control, *opts).with_sensor_period(sensor_period);
    let mut outcome = RunOutcome {
        stop: Stop::Completed,
        t: 0.0,
        max_roll: 0.0,
        max_pitch: 0.0,
    };
    if let Err(e) = driver.start_with(sys, integ, t, y, &mut on_sensor) {
        outcome.stop = Stop::Failed(e);
        return outcome;
    }
    loop {
        outcome.t = t;
        outcome.max_roll = outcome.max_roll.max(y[3].abs());
        outcome.max_pitch = outcome.max_pitch.max(y[4].abs());
        if let Err(e) = emit(sys, t, y, &mut scratch, &mut output) {
            outcome.stop = Stop::Failed(e);
            return outcome;
        }
        if driver.finished(t) {
            return outcome;
        }
        if interrupt.load(Ordering::Relaxed) {
            outcome.stop = Stop::Interrupted { t };
            return outcome;
        }
        if let Err(e) = driver.advance_with(sys, integ, &mut t, y, &mut on_sensor) {
            outcome.t = e.time();
            outcome.stop = Stop::Failed(e);
            return outcome;
        }
    }
}

/// The row at (t, y): one right-hand side evaluates the contact reports
/// there, then `output` takes them.
fn emit<P, H, F>(
    sys: &mut RoverSystem<P, H>,
    t: f64,
    y: &[f64],
    scratch: &mut [f64],
    output: &mut F,
) -> Result<(), RunError>
where
    P: Plant,
    H: HeightField,
    F: FnMut(&OutputRow<'_, P, H>) -> std::io::Result<()>,
{
    sys.evaluate_at(t, y, scratch)?;
    output(&OutputRow { t, y, system: sys }).map_err(|e| RunError::Output {
        t,
        message: e.to_string(),
    })
}
