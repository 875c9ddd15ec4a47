//! Why a right-hand side or a run failed.

use rover_dynamics::plant::PlantError;
use rover_dynamics::wheel_ground::WheelOffMap;

/// A right-hand-side evaluation failed.
#[derive(Clone, Copy, Debug, PartialEq, thiserror::Error)]
pub enum SimError {
    /// The plant could not produce accelerations.
    #[error("{0}")]
    Plant(PlantError),
    /// A wheel left the terrain map.
    #[error("wheel {} left the terrain: {}", .0.wheel + 1, .0.off)]
    OffMap(WheelOffMap),
}

/// An open-loop command the rover cannot take
/// ([`RoverSystem::set_torques`](crate::sim::RoverSystem::set_torques),
/// [`RoverSystem::set_steering`](crate::sim::RoverSystem::set_steering)).
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum CommandError {
    /// One value per wheel is needed.
    #[error(
        "{what}: the rover has {wheels} wheels, {given} values were given (one per wheel, the description's order)"
    )]
    Count {
        /// Which command.
        what: &'static str,
        /// Wheels of the rover.
        wheels: usize,
        /// Values given.
        given: usize,
    },
    /// A value is NaN or infinite.
    #[error("{what}: wheel {wheel}'s value is {value}; commands must be finite")]
    NotFinite {
        /// Which command.
        what: &'static str,
        /// Wheel (1-based).
        wheel: usize,
        /// The value.
        value: f64,
    },
    /// A steering angle for a wheel that does not steer.
    #[error(
        "steering: wheel {wheel} is not steerable (`steerable = true` in the description), its angle must be 0, got {value} rad"
    )]
    NotSteerable {
        /// Wheel (1-based).
        wheel: usize,
        /// The angle \[rad\].
        value: f64,
    },
}

/// Slip above which a wheel on a soil does not advance.
pub const EMBEDDED_SLIP: f64 = 0.95;
/// Time every wheel on the ground must slip above [`EMBEDDED_SLIP`] for the
/// rover to be embedded \[s\].
pub const EMBEDDED_TIME: f64 = 5.0;
/// Sinkage, as a fraction of the wheel's radius, past which a wheel is embedded.
pub const EMBEDDED_SINKAGE: f64 = 0.5;

/// Why a run stopped before its end time. Every variant names the time.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum RunError {
    /// |φ| or |θ| passed the roll-over limit.
    #[error(
        "the rover rolled over at t = {t:.3} s: roll {roll_deg:.1}°, pitch {pitch_deg:.1}° (limit {limit_deg:.0}°)"
    )]
    RolledOver {
        /// Time \[s\].
        t: f64,
        /// Roll φ \[deg\].
        roll_deg: f64,
        /// Pitch θ \[deg\].
        pitch_deg: f64,
        /// The limit \[deg\].
        limit_deg: f64,
    },
    /// The attitude jumped past half a turn between two events: no
    /// roll-over (a rover tips through the limit first) but a numerical
    /// blow-up.
    #[error(
        "the run stopped at t = {t:.6} s: the attitude jumped to roll {roll_deg:.1}°, pitch {pitch_deg:.1}° since the previous event: the integration diverged; with a fixed-step method, shorten `step` (1e-4 s suits a rover), or use the adaptive `[integrator.bdf]`"
    )]
    Diverged {
        /// Time \[s\].
        t: f64,
        /// Roll φ \[deg\].
        roll_deg: f64,
        /// Pitch θ \[deg\].
        pitch_deg: f64,
    },
    /// The integrator stopped (a non-finite state, a failing right-hand side, a step too small).
    #[error("the run stopped at t = {t:.6} s: {message}")]
    Integration {
        /// Time \[s\].
        t: f64,
        /// What happened.
        message: String,
        /// The step-size control gave up (see
        /// [`IntegrateError::is_step_control`](rover_integrate::IntegrateError::is_step_control)).
        step_control: bool,
    },
    /// On a soil, the rover could not advance: every wheel on the ground
    /// slipped above [`EMBEDDED_SLIP`] for [`EMBEDDED_TIME`], or a wheel sank
    /// past half its radius.
    #[error(
        "the rover is embedded at t = {t:.3} s, at X = {x:.3} m, Y = {y:.3} m: {why}\n  = help: a gentler slope, a lighter rover, wider or larger wheels, or a firmer soil; summary.json has each wheel's slip and sinkage"
    )]
    Embedded {
        /// Time \[s\].
        t: f64,
        /// G's position X \[m\].
        x: f64,
        /// G's position Y \[m\].
        y: f64,
        /// Which wheels, and how.
        why: String,
    },
    /// The output sink failed (disk full, closed pipe).
    #[error("writing the output failed at t = {t:.3} s: {message}")]
    Output {
        /// Time \[s\].
        t: f64,
        /// The I/O error.
        message: String,
    },
}

impl RunError {
    /// The simulation time of the failure \[s\].
    pub fn time(&self) -> f64 {
        match self {
            RunError::RolledOver { t, .. }
            | RunError::Embedded { t, .. }
            | RunError::Diverged { t, .. }
            | RunError::Integration { t, .. }
            | RunError::Output { t, .. } => *t,
        }
    }
}
