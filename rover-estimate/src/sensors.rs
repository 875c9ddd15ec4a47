//! What a rover's sensors read: their declaration ([`SensorConfig`], the
//! `[sensors]` table of a scenario, in the units of a datasheet) and one
//! instant's readings ([`SensorSample`], in SI).
//!
//! Every sensor but the sparse fixes is read at [`SensorConfig::rate`]:
//! - an IMU ([`ImuConfig`]) at a point of the body, its axes turned from
//!   the body's: the angular velocity (gyros) and the specific force
//!   (accelerometers, `a − g` in the IMU's axes), each with white noise and
//!   a bias that wanders as a first-order Gauss–Markov process;
//! - wheel encoders ([`EncoderConfig`]): each wheel's rotation since the
//!   start, quantized (they see slip where the soil law makes it);
//! - suspension encoders ([`SuspensionEncoderConfig`]): each suspension
//!   coordinate, with noise, quantized;
//! - sparse fixes at their own rates: a position ([`PositionFixConfig`]:
//!   visual odometry, a total station) and a heading
//!   ([`HeadingFixConfig`]: a sun sensor).

use alloc::vec::Vec;

/// Standard gravity \[m/s²\], the unit `g` of accelerometer datasheets
/// (whatever the planet).
pub const STANDARD_GRAVITY: f64 = 9.806_65;

/// The sensors of a rover.
#[derive(Clone, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Deserialize, serde::Serialize))]
#[cfg_attr(feature = "serde", serde(deny_unknown_fields))]
pub struct SensorConfig {
    /// Seed of the sensors' noise: the same seed, the same readings.
    #[cfg_attr(feature = "serde", serde(default))]
    pub seed: u64,
    /// Rate at which the IMU, the encoders and the suspension encoders are
    /// read \[Hz\] (100 by default).
    #[cfg_attr(feature = "serde", serde(default = "default_rate"))]
    pub rate: f64,
    /// The inertial measurement unit, if the rover has one.
    #[cfg_attr(feature = "serde", serde(default))]
    pub imu: Option<ImuConfig>,
    /// The wheel encoders, if the rover has them.
    #[cfg_attr(feature = "serde", serde(default))]
    pub wheel_encoders: Option<EncoderConfig>,
    /// The suspension encoders, if the rover has them.
    #[cfg_attr(feature = "serde", serde(default))]
    pub suspension_encoders: Option<SuspensionEncoderConfig>,
    /// A sparse position fix.
    #[cfg_attr(feature = "serde", serde(default))]
    pub position_fix: Option<PositionFixConfig>,
    /// A sparse heading fix.
    #[cfg_attr(feature = "serde", serde(default))]
    pub heading_fix: Option<HeadingFixConfig>,
}

#[cfg(feature = "serde")]
fn default_rate() -> f64 {
    100.0
}

/// An IMU, declared as its datasheet gives it.
#[derive(Clone, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Deserialize, serde::Serialize))]
#[cfg_attr(feature = "serde", serde(deny_unknown_fields))]
pub struct ImuConfig {
    /// Gyro white noise, the angle random walk [°/√h].
    pub gyro_noise_deg_per_sqrt_h: f64,
    /// Gyro bias instability, the bias's standard deviation [°/h].
    pub gyro_bias_deg_per_h: f64,
    /// Accelerometer white noise density [µg/√Hz].
    pub accel_noise_ug_per_sqrt_hz: f64,
    /// Accelerometer bias instability, the bias's standard deviation \[mg\].
    pub accel_bias_mg: f64,
    /// Correlation time of the biases' wander \[s\] (300 by default).
    #[cfg_attr(feature = "serde", serde(default = "default_bias_time"))]
    pub bias_time: f64,
    /// The IMU's origin in body axes, from G \[m\].
    #[cfg_attr(feature = "serde", serde(default))]
    pub position: [f64; 3],
    /// The IMU's axes as roll, pitch, yaw from the body's [°] (docs/MODEL.md
    /// §1's order).
    #[cfg_attr(feature = "serde", serde(default))]
    pub orientation_deg: [f64; 3],
}

#[cfg(feature = "serde")]
fn default_bias_time() -> f64 {
    300.0
}

impl ImuConfig {
    /// Gyro white-noise density [rad/s/√Hz] (= rad/√s).
    pub fn gyro_noise_density(&self) -> f64 {
        self.gyro_noise_deg_per_sqrt_h.to_radians() / 60.0
    }
    /// Gyro bias standard deviation \[rad/s\].
    pub fn gyro_bias_sigma(&self) -> f64 {
        self.gyro_bias_deg_per_h.to_radians() / 3600.0
    }
    /// Accelerometer white-noise density [m/s²/√Hz].
    pub fn accel_noise_density(&self) -> f64 {
        self.accel_noise_ug_per_sqrt_hz * 1e-6 * STANDARD_GRAVITY
    }
    /// Accelerometer bias standard deviation [m/s²].
    pub fn accel_bias_sigma(&self) -> f64 {
        self.accel_bias_mg * 1e-3 * STANDARD_GRAVITY
    }
}

/// Wheel encoders (every wheel has one).
#[derive(Clone, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Deserialize, serde::Serialize))]
#[cfg_attr(feature = "serde", serde(deny_unknown_fields))]
pub struct EncoderConfig {
    /// One count \[rad\].
    pub resolution: f64,
}

/// Suspension encoders (every suspension coordinate has one), in the
/// coordinate's unit (rad, or m for a linear coordinate).
#[derive(Clone, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Deserialize, serde::Serialize))]
#[cfg_attr(feature = "serde", serde(deny_unknown_fields))]
pub struct SuspensionEncoderConfig {
    /// One count (rad, or m).
    pub resolution: f64,
    /// White noise's standard deviation (rad, or m).
    #[cfg_attr(feature = "serde", serde(default))]
    pub noise: f64,
}

/// A sparse position fix.
#[derive(Clone, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Deserialize, serde::Serialize))]
#[cfg_attr(feature = "serde", serde(deny_unknown_fields))]
pub struct PositionFixConfig {
    /// Fixes per second \[Hz\].
    pub rate: f64,
    /// Standard deviation of each coordinate \[m\].
    pub sigma: f64,
}

/// A sparse heading fix.
#[derive(Clone, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Deserialize, serde::Serialize))]
#[cfg_attr(feature = "serde", serde(deny_unknown_fields))]
pub struct HeadingFixConfig {
    /// Fixes per second \[Hz\].
    pub rate: f64,
    /// Standard deviation of the yaw ψ \[rad\].
    pub sigma: f64,
}

/// One instant's readings, in SI. A sensor the rover does not have, or a
/// fix not due, reads `None` or an empty slice.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct SensorSample {
    /// Time \[s\].
    pub t: f64,
    /// Gyros: angular velocity in the IMU's axes \[rad/s\].
    pub gyro: Option<[f64; 3]>,
    /// Accelerometers: specific force `a − g` in the IMU's axes [m/s²].
    pub accel: Option<[f64; 3]>,
    /// Each wheel's rotation since the start, quantized \[rad\], positive
    /// rolling forwards.
    pub wheel_angles: Vec<f64>,
    /// Each suspension coordinate (rad, or m).
    pub suspension: Vec<f64>,
    /// A position fix of G, inertial \[m\].
    pub position: Option<[f64; 3]>,
    /// A heading fix, the yaw ψ \[rad\].
    pub heading: Option<f64>,
    /// The motor torques the rover's computer commanded [N·m], in force
    /// until the next sample.
    pub torques: Vec<f64>,
    /// The steering angles it commanded \[rad\].
    pub steering: Vec<f64>,
}
