//! The filter's tuning ([`FilterConfig`]) and its initial uncertainty
//! ([`InitialSigma`]), each a standard deviation per group of the error
//! state, in SI.

use super::EstimateError;

/// The filter's tuning: how many linearly implicit steps a prediction
/// takes, and the process noise of each group of the error state, as the
/// standard deviation a component gains over one second of white noise
/// (its spectral density's square root): `P += q²·dt` on the diagonal.
///
/// The noise stands for what the model does not know: the commands held
/// over a step while the rover's own loops move them, the terrain between
/// its map's nodes, a soil's or tyre's parameters, and the step's own
/// error. Two sets are tuned (docs/ESTIMATE.md, "Tuning"):
/// [`FilterConfig::default`] for a model that is the rover's own (its
/// terrain map true, rigid ground): little noise, most of it where the
/// commands move; [`FilterConfig::approximate_model`] for a model that
/// is not (a smoothed map, a soil whose law only approximates the
/// ground): a noise on every group.
#[derive(Clone, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Deserialize, serde::Serialize))]
#[cfg_attr(feature = "serde", serde(default, deny_unknown_fields))]
pub struct FilterConfig {
    /// Linearly implicit Euler steps per prediction, on the Jacobian of
    /// its start (1: one step of `dt`).
    pub substeps: usize,
    /// A Jacobian of the model is taken every this many predictions (1:
    /// at each); in between the last one serves the step's matrix, its
    /// transition and the accelerometers' rows, the right-hand side being
    /// evaluated afresh. The Jacobian is most of a step's cost.
    pub jacobian_every: usize,
    /// G's position \[m/√s\].
    pub position_noise: f64,
    /// The attitude, each axis of the small rotation δθ \[rad/√s\].
    pub attitude_noise: f64,
    /// The suspension coordinates [rad/√s, or m/√s].
    pub suspension_noise: f64,
    /// G's velocity, body components [m/s/√s].
    pub velocity_noise: f64,
    /// The body's angular velocity, body components [rad/s/√s].
    pub angular_velocity_noise: f64,
    /// The suspension rates [rad/s/√s, or m/s/√s].
    pub suspension_rate_noise: f64,
    /// The wheels' spins on a soil [rad/s/√s].
    pub spin_noise: f64,
    /// A wheel encoder's rate against the model's \[rad/s\], on top of its
    /// quantization: the model's rate is taken at the interval's end, the
    /// reading is its mean over the interval.
    pub wheel_rate_sigma: f64,
    /// An accelerometer reading against the model's acceleration [m/s²],
    /// on top of the sensor's noise: the model's `ẇ` at the estimate
    /// carries the commands held over the step, the terrain between the
    /// map's nodes and the linearization's error, and a stiff tyre makes
    /// it swing with every small error of the state.
    pub accel_model_sigma: f64,
    /// A commanded motor torque's error over one prediction [N·m], each
    /// wheel's independent and independent between predictions: the
    /// command is held over the step while the rover's motor loop moves
    /// it. It enters the covariance through the model's own response to a
    /// torque, `P += dt²·σ²·b_k·b_kᵀ` with `b_k = ∂f/∂τ_k`, so that the
    /// uncertainty goes where a torque moves the rover: along its track,
    /// in yaw where the wheels skid, into the suspensions by the reaction.
    pub torque_sigma: f64,
    /// Predictions between two evaluations of `∂f/∂τ` (one right-hand
    /// side per wheel, by differences): the response to a torque changes
    /// with the contacts, slowly against the step.
    pub torque_response_every: usize,
    /// How much of a torque's last change between two predictions the
    /// held torque may be off by: the command is held over the step
    /// while the rover's loop ramps it (½: a steady ramp's held value is
    /// off by half its change, on average over the step). Adds
    /// `(scale·Δτ_k)²` to `torque_sigma²`, so that the uncertainty grows
    /// where the commands move — a wheel striking a bump makes the speed
    /// loop push — and not while they hold.
    pub torque_change_scale: f64,
}

impl Default for FilterConfig {
    /// The tuning for a model that is the rover's own: tuned on the
    /// paper's Fig. 13 run (swing4 slip-steered on rough ground at
    /// 0.05 m/s, its true map) with the commands sampled at 100 Hz, over
    /// sixteen seeds of its sensors.
    fn default() -> Self {
        Self {
            substeps: 2,
            jacobian_every: 1,
            position_noise: 3e-7,
            attitude_noise: 1.8e-6,
            suspension_noise: 1e-6,
            velocity_noise: 8.25e-5,
            angular_velocity_noise: 6e-4,
            suspension_rate_noise: 0.016,
            spin_noise: 0.5,
            wheel_rate_sigma: 0.001,
            accel_model_sigma: 0.00135,
            torque_sigma: 0.00048,
            torque_response_every: 10,
            torque_change_scale: 0.5,
        }
    }
}

impl FilterConfig {
    /// The tuning for a model that only approximates the rover's world:
    /// a map smoothed below its features, a soil law over real sand.
    /// A noise on every group, none through the torques (on a soil the
    /// wheel loops' torques move with every change of slip).
    pub fn approximate_model() -> Self {
        Self {
            substeps: 1,
            jacobian_every: 1,
            position_noise: 1e-3,
            attitude_noise: 1e-3,
            suspension_noise: 1e-3,
            velocity_noise: 0.02,
            angular_velocity_noise: 0.05,
            suspension_rate_noise: 0.05,
            spin_noise: 0.5,
            wheel_rate_sigma: 0.02,
            accel_model_sigma: 0.05,
            torque_sigma: 0.0,
            torque_response_every: 10,
            torque_change_scale: 0.0,
        }
    }
}

/// The initial state's standard deviation per group of the error state
/// (the IMU's biases start at their datasheet σ).
#[derive(Clone, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Deserialize, serde::Serialize))]
#[cfg_attr(feature = "serde", serde(default, deny_unknown_fields))]
pub struct InitialSigma {
    /// G's position \[m\].
    pub position: f64,
    /// Each axis of the attitude's small rotation \[rad\].
    pub attitude: f64,
    /// The suspension coordinates (rad, or m).
    pub suspension: f64,
    /// G's velocity \[m/s\].
    pub velocity: f64,
    /// The angular velocity \[rad/s\].
    pub angular_velocity: f64,
    /// The suspension rates (rad/s, or m/s).
    pub suspension_rate: f64,
    /// The wheels' spins on a soil \[rad/s\].
    pub spin: f64,
}

impl Default for InitialSigma {
    /// A start the filter knows: the pose and attitude where the map's
    /// frame says the rover stands (a rover's map frame is where it
    /// started); the rest as the sensors will soon tell.
    fn default() -> Self {
        Self {
            position: 1e-6,
            attitude: 3e-6,
            ..Self::approximate_model()
        }
    }
}

impl InitialSigma {
    /// A start placed on an approximate model (a smoothed map, a soil):
    /// a millimetre and a milliradian.
    pub fn approximate_model() -> Self {
        Self {
            position: 0.001,
            attitude: 0.001,
            suspension: 0.01,
            velocity: 0.01,
            angular_velocity: 0.01,
            suspension_rate: 0.01,
            spin: 0.1,
        }
    }
}

/// `value` finite and ≥ 0 (or > 0 when `positive`), else a located error.
pub(crate) fn check<E>(
    field: &'static str,
    value: f64,
    positive: bool,
) -> Result<f64, EstimateError<E>> {
    let fine = value.is_finite() && if positive { value > 0.0 } else { value >= 0.0 };
    if fine {
        Ok(value)
    } else {
        Err(EstimateError::Config {
            field,
            value,
            expected: if positive {
                "positive and finite"
            } else {
                "zero or positive, and finite"
            },
        })
    }
}

impl FilterConfig {
    /// Whether the torques carry a noise (`torque_sigma` or
    /// `torque_change_scale` above 0): the prediction then needs `∂f/∂τ`.
    pub(crate) fn torque_noise(&self) -> bool {
        self.torque_sigma > 0.0 || self.torque_change_scale > 0.0
    }

    /// Every field in range.
    pub(crate) fn validate<E>(&self) -> Result<(), EstimateError<E>> {
        if self.substeps == 0 {
            return Err(EstimateError::Config {
                field: "filter.substeps",
                value: 0.0,
                expected: "at least 1",
            });
        }
        if self.jacobian_every == 0 {
            return Err(EstimateError::Config {
                field: "filter.jacobian_every",
                value: 0.0,
                expected: "at least 1",
            });
        }
        check("filter.position_noise", self.position_noise, false)?;
        check("filter.accel_model_sigma", self.accel_model_sigma, false)?;
        check("filter.torque_sigma", self.torque_sigma, false)?;
        check(
            "filter.torque_change_scale",
            self.torque_change_scale,
            false,
        )?;
        if self.torque_response_every == 0 {
            return Err(EstimateError::Config {
                field: "filter.torque_response_every",
                value: 0.0,
                expected: "at least 1",
            });
        }
        check("filter.attitude_noise", self.attitude_noise, false)?;
        check("filter.suspension_noise", self.suspension_noise, false)?;
        check("filter.velocity_noise", self.velocity_noise, false)?;
        check(
            "filter.angular_velocity_noise",
            self.angular_velocity_noise,
            false,
        )?;
        check(
            "filter.suspension_rate_noise",
            self.suspension_rate_noise,
            false,
        )?;
        check("filter.spin_noise", self.spin_noise, false)?;
        check("filter.wheel_rate_sigma", self.wheel_rate_sigma, false)?;
        Ok(())
    }
}

impl InitialSigma {
    /// Every σ positive: the covariance starts positive definite.
    pub(crate) fn validate<E>(&self) -> Result<(), EstimateError<E>> {
        check("initial.position", self.position, true)?;
        check("initial.attitude", self.attitude, true)?;
        check("initial.suspension", self.suspension, true)?;
        check("initial.velocity", self.velocity, true)?;
        check("initial.angular_velocity", self.angular_velocity, true)?;
        check("initial.suspension_rate", self.suspension_rate, true)?;
        check("initial.spin", self.spin, true)?;
        Ok(())
    }
}
