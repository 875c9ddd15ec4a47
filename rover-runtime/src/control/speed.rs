//! The longitudinal speed loop (MODEL.md §8, paper §5.1).

use serde::{Deserialize, Serialize};

use super::{Distribution, Profile};

/// A P or PI loop on the body's forward speed v_x issuing the mean wheel
/// torque τ_0 (N·m per wheel):
/// ```text
/// τ_0 = K_p·(V − v_x) + K_i·∫(V − v_x) dt
/// ```
/// The integral is a state of the ODE (so adaptive integrators see a smooth
/// right-hand side); it is clamped so that K_i·∫ never exceeds the largest
/// wheel torque (anti-windup). With V = 0 the integral is the distance
/// rolled, so a PI loop brings a parked rover back to where it stopped.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SpeedConfig {
    /// Speed set-point V [m/s] against time after settling.
    #[serde(default)]
    pub speed: Profile,
    /// Proportional gain K_p [N·m per m/s, per wheel]. The default, 10, gives
    /// Example 1 (33.6 kg, six 9 cm wheels) a time constant of
    /// m·R_w/(n·K_p) ≈ 0.05 s.
    #[serde(default = "default_kp")]
    pub kp: f64,
    /// Integral gain K_i [N·m per m, per wheel]; 0 is the paper's P loop.
    #[serde(default)]
    pub ki: f64,
    /// How τ_0 is shared among the wheels.
    #[serde(default)]
    pub distribution: Distribution,
    /// Anti-spin only: the slip above which a wheel's share is cut
    /// (default [`DEFAULT_SLIP_THRESHOLD`](super::DEFAULT_SLIP_THRESHOLD)), in [0, 1).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub slip_threshold: Option<f64>,
    /// Anti-spin only: the width of slip over which the cut share falls to
    /// none (default [`DEFAULT_SLIP_BAND`](super::DEFAULT_SLIP_BAND)), > 0.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub slip_band: Option<f64>,
}

fn default_kp() -> f64 {
    10.0
}

impl Default for SpeedConfig {
    fn default() -> Self {
        Self {
            speed: Profile::default(),
            kp: default_kp(),
            ki: 0.0,
            distribution: Distribution::default(),
            slip_threshold: None,
            slip_band: None,
        }
    }
}

/// A constant set-point V [m/s] with the default gains and distribution.
impl From<f64> for SpeedConfig {
    fn from(speed: f64) -> Self {
        Self {
            speed: Profile::Constant(speed),
            ..Self::default()
        }
    }
}
