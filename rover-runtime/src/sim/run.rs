//! The driver: advance the system to each event (output instant, controller
//! sample, command breakpoint), check the stop conditions, emit rows.

use std::sync::atomic::{AtomicBool, Ordering};

use rover_dynamics::HeightField;
use rover_dynamics::plant::Plant;

use rover_integrate::{Integrator, OdeSystem};

use super::error::RunError;
use super::system::RoverSystem;

/// Options of a run.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RunOptions {
    /// End time \[s\].
    pub duration: f64,
    /// Interval between output rows \[s\].
    pub output_step: f64,
    /// |φ| or |θ| beyond this is a roll-over \[rad\] (MODEL.md §1: 80°).
    pub rollover_limit: f64,
}

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

/// Run `sys` from (0, y) to `opts.duration`, calling `output` at t = 0 and
/// every `opts.output_step`. `interrupt` is polled between events.
pub fn run<P, H, I, F>(
    sys: &mut RoverSystem<P, H>,
    integ: &mut I,
    y: &mut [f64],
    opts: &RunOptions,
    interrupt: &AtomicBool,
    mut output: F,
) -> RunOutcome
where
    P: Plant,
    H: HeightField,
    I: Integrator,
    F: FnMut(&OutputRow<'_, P, H>) -> std::io::Result<()>,
{
    let n = sys.dof();
    let mut t = 0.0;
    let mut scratch = vec![0.0; y.len()];
    let mut breaks: Vec<f64> = sys
        .control
        .breakpoints()
        .into_iter()
        .filter(|&b| b > 0.0 && b < opts.duration)
        .collect();
    breaks.sort_by(f64::total_cmp);
    let sample = sys.control.sample_period();
    let mut k_out = 0u64;
    let mut k_sample = 0u64;
    let mut next_break = 0usize;
    let mut outcome = RunOutcome {
        stop: Stop::Completed,
        t: 0.0,
        max_roll: 0.0,
        max_pitch: 0.0,
    };
    let fail = |outcome: &mut RunOutcome, t: f64, e: RunError| {
        outcome.stop = Stop::Failed(e);
        outcome.t = t;
    };
    loop {
        let t_out = k_out as f64 * opts.output_step;
        // Events at t: sample, output.
        if let Some(dt) = sample
            && (k_sample as f64 * dt - t).abs() <= 1e-12 * (1.0 + t)
        {
            let (x, rest) = y.split_at(n);
            if sys.control.sample(t, x, &rest[..n], &mut sys.plant) {
                integ.restart();
            }
            k_sample += 1;
        }
        // The end of the run is always a row, on an output instant or not
        // (an output step that does not divide the duration, or exceeds it).
        let at_output = (t_out - t).abs() <= 1e-12 * (1.0 + t);
        if at_output || t >= opts.duration {
            let (roll, pitch) = (y[3], y[4]);
            outcome.max_roll = outcome.max_roll.max(roll.abs());
            outcome.max_pitch = outcome.max_pitch.max(pitch.abs());
            if let Err(e) = sys.rhs(t, y, &mut scratch) {
                fail(
                    &mut outcome,
                    t,
                    RunError::Integration {
                        t,
                        message: e.to_string(),
                        step_control: false,
                    },
                );
                return outcome;
            }
            if let Err(e) = output(&OutputRow { t, y, system: sys }) {
                fail(
                    &mut outcome,
                    t,
                    RunError::Output {
                        t,
                        message: e.to_string(),
                    },
                );
                return outcome;
            }
            k_out += 1;
        }
        if t >= opts.duration {
            break;
        }
        if interrupt.load(Ordering::Relaxed) {
            outcome.stop = Stop::Interrupted { t };
            outcome.t = t;
            return outcome;
        }
        // Next event.
        while next_break < breaks.len() && breaks[next_break] <= t {
            next_break += 1;
        }
        let mut target = (k_out as f64 * opts.output_step).min(opts.duration);
        if let Some(dt) = sample {
            target = target.min(k_sample as f64 * dt);
        }
        // A breakpoint on (or within rounding of) the next output instant
        // is one too: the integrator must restart there, not carry its
        // history across the jump (a settling time on an output instant
        // used to, and could stall BDF's step control right before it).
        let at_break =
            next_break < breaks.len() && breaks[next_break] <= target + 1e-12 * (1.0 + target);
        if at_break {
            target = breaks[next_break];
        }
        sys.set_next_break(at_break.then_some(target));
        let advanced = integ.advance(sys, &mut t, y, target);
        sys.set_next_break(None);
        if let Err(e) = advanced {
            let te = e.time().unwrap_or(t);
            fail(
                &mut outcome,
                te,
                RunError::Integration {
                    t: te,
                    message: e.to_string(),
                    step_control: e.is_step_control(),
                },
            );
            return outcome;
        }
        if at_break {
            integ.restart();
        }
        let (roll, pitch) = (y[3], y[4]);
        // Past half a turn between two events is no roll-over but a
        // numerical blow-up: a rover tips through the limit first.
        if roll.abs() > std::f64::consts::PI || pitch.abs() > std::f64::consts::PI {
            let e = RunError::Integration {
                t,
                message: format!(
                    "the attitude jumped to roll {:.1}°, pitch {:.1}° since the previous event: the integration diverged; with a fixed-step method, shorten `step` (1e-4 s suits a rover), or use the adaptive `[integrator.bdf]`",
                    roll.to_degrees(),
                    pitch.to_degrees()
                ),
                step_control: false,
            };
            fail(&mut outcome, t, e);
            return outcome;
        }
        if roll.abs() > opts.rollover_limit || pitch.abs() > opts.rollover_limit {
            let e = RunError::RolledOver {
                t,
                roll_deg: roll.to_degrees(),
                pitch_deg: pitch.to_degrees(),
                limit_deg: opts.rollover_limit.to_degrees(),
            };
            fail(&mut outcome, t, e);
            return outcome;
        }
    }
    outcome.t = t;
    outcome
}
