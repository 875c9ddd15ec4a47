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
/// error. The defaults keep the filter consistent (its NEES within the
/// chi-square band) on the paper's Fig. 13 run (swing4 slip-steered on
/// rough ground at 0.05 m/s) with the commands sampled at 100 Hz.
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
}

impl Default for FilterConfig {
    fn default() -> Self {
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
    fn default() -> Self {
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
