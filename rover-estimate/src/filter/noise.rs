//! The sensors' noises as the filter uses them: each declared sensor's
//! discrete variance per reading, from its [`SensorConfig`] checked once.

use rover_dynamics::attitude::Attitude;
use rover_dynamics::linalg::{M3, transpose};

use super::EstimateError;
use super::config::check;
use crate::sensors::{ImuConfig, SensorConfig};

/// The IMU's noises, place and axes.
#[derive(Clone, Copy, Debug)]
pub(crate) struct ImuNoise {
    /// One gyro reading's white-noise variance [(rad/s)²]: the density²
    /// times the sampling rate (white noise of density `q` averaged over
    /// `1/rate` has variance `q²·rate`).
    pub gyro_variance: f64,
    /// One accelerometer reading's variance [(m/s²)²], likewise.
    pub accel_variance: f64,
    /// The gyro bias's standard deviation \[rad/s\].
    pub gyro_bias_sigma: f64,
    /// The accelerometer bias's standard deviation [m/s²].
    pub accel_bias_sigma: f64,
    /// The biases' correlation time \[s\].
    pub bias_time: f64,
    /// The IMU's origin in body axes, from G \[m\].
    pub position: [f64; 3],
    /// Body components → IMU components: `C = R_imuᵀ`, `R_imu` the
    /// rotation of the IMU's roll, pitch, yaw from the body's (MODEL.md
    /// §1's order), which takes IMU components to body components.
    pub to_imu: M3<f64>,
}

/// A suspension encoder: its count, its white noise, and the interval
/// between its readings.
#[derive(Clone, Copy, Debug)]
pub(crate) struct SuspensionNoise {
    /// One count [rad, or m].
    pub resolution: f64,
    /// The white noise's σ².
    pub variance: f64,
    /// Between two readings \[s\].
    pub interval: f64,
}

impl SuspensionNoise {
    /// One reading's variance when the coordinate moves at `rate`
    /// (its magnitude, the estimate's uncertainty included): the count's
    /// uniform error `res²/12`, which stays the same from reading to
    /// reading while the coordinate sits within one count, so that the
    /// `res/(|rate|·Δt)` readings taken within a count tell what one
    /// does; plus the white noise.
    pub fn variance(&self, rate: f64) -> f64 {
        let res = self.resolution;
        let readings_per_count = res / (rate * self.interval);
        // At rest (a rate of 0, never with a positive covariance) the
        // reading still bounds the coordinate to its count, once.
        let shared = readings_per_count.clamp(1.0, 1e9);
        res * res / 12.0 * shared + self.variance
    }
}

/// Every declared sensor's noise.
#[derive(Clone, Debug)]
pub(crate) struct SensorNoise {
    pub imu: Option<ImuNoise>,
    /// A wheel encoder's count \[rad\].
    pub encoder_resolution: Option<f64>,
    /// The suspension encoders' quantization.
    pub suspension: Option<SuspensionNoise>,
    /// One coordinate of a position fix \[m²\].
    pub position_variance: Option<f64>,
    /// A heading fix \[rad²\].
    pub heading_variance: Option<f64>,
}

impl SensorNoise {
    /// The noises of `config`, each field checked.
    pub(crate) fn new<E>(config: &SensorConfig) -> Result<Self, EstimateError<E>> {
        let rate = check("sensors.rate", config.rate, true)?;
        let imu = match &config.imu {
            Some(imu) => Some(imu_noise(imu, rate)?),
            None => None,
        };
        let encoder_resolution = match &config.wheel_encoders {
            Some(e) => Some(check(
                "sensors.wheel_encoders.resolution",
                e.resolution,
                true,
            )?),
            None => None,
        };
        let suspension = match &config.suspension_encoders {
            Some(s) => {
                let resolution = check(
                    "sensors.suspension_encoders.resolution",
                    s.resolution,
                    false,
                )?;
                let noise = check("sensors.suspension_encoders.noise", s.noise, false)?;
                let variance = noise * noise;
                check(
                    "sensors.suspension_encoders.noise",
                    resolution * resolution / 12.0 + variance,
                    true,
                )?;
                Some(SuspensionNoise {
                    resolution,
                    variance,
                    interval: 1.0 / rate,
                })
            }
            None => None,
        };
        let position_variance = match &config.position_fix {
            Some(p) => {
                check("sensors.position_fix.rate", p.rate, true)?;
                let s = check("sensors.position_fix.sigma", p.sigma, true)?;
                Some(check("sensors.position_fix.sigma", s * s, true)?)
            }
            None => None,
        };
        let heading_variance = match &config.heading_fix {
            Some(h) => {
                check("sensors.heading_fix.rate", h.rate, true)?;
                let s = check("sensors.heading_fix.sigma", h.sigma, true)?;
                Some(check("sensors.heading_fix.sigma", s * s, true)?)
            }
            None => None,
        };
        Ok(Self {
            imu,
            encoder_resolution,
            suspension,
            position_variance,
            heading_variance,
        })
    }
}

fn imu_noise<E>(imu: &ImuConfig, rate: f64) -> Result<ImuNoise, EstimateError<E>> {
    check(
        "sensors.imu.gyro_noise_deg_per_sqrt_h",
        imu.gyro_noise_deg_per_sqrt_h,
        true,
    )?;
    check(
        "sensors.imu.accel_noise_ug_per_sqrt_hz",
        imu.accel_noise_ug_per_sqrt_hz,
        true,
    )?;
    // A bias of σ 0 would be known exactly: a zero row of the covariance.
    check(
        "sensors.imu.gyro_bias_deg_per_h",
        imu.gyro_bias_deg_per_h,
        true,
    )?;
    check("sensors.imu.accel_bias_mg", imu.accel_bias_mg, true)?;
    let bias_time = check("sensors.imu.bias_time", imu.bias_time, true)?;
    for v in imu.position {
        check("sensors.imu.position", v.abs(), false)?;
    }
    for v in imu.orientation_deg {
        check("sensors.imu.orientation_deg", v.abs(), false)?;
    }
    let gyro = imu.gyro_noise_density();
    let accel = imu.accel_noise_density();
    let [roll, pitch, yaw] = imu.orientation_deg.map(f64::to_radians);
    // A variance that underflows to 0 would make a reading exact.
    let gyro_variance = check(
        "sensors.imu.gyro_noise_deg_per_sqrt_h",
        gyro * gyro * rate,
        true,
    )?;
    let accel_variance = check(
        "sensors.imu.accel_noise_ug_per_sqrt_hz",
        accel * accel * rate,
        true,
    )?;
    Ok(ImuNoise {
        gyro_variance,
        accel_variance,
        gyro_bias_sigma: imu.gyro_bias_sigma(),
        accel_bias_sigma: imu.accel_bias_sigma(),
        bias_time,
        position: imu.position,
        to_imu: transpose(&Attitude::new(roll, pitch, yaw).rotation()),
    })
}

#[cfg(test)]
mod tests {
    use super::SuspensionNoise;

    /// A coordinate that crosses a count or more between readings reads
    /// with the count's uniform variance `res²/12`; one that takes `k`
    /// readings to cross a count, with `k` times it (its `k` readings
    /// share one error); at rest, bounded; the white noise adds.
    #[test]
    fn a_slow_coordinate_shares_its_counts_error_between_readings() {
        let res = 0.002;
        let q = SuspensionNoise {
            resolution: res,
            variance: 0.0,
            interval: 0.01,
        };
        let uniform = res * res / 12.0;
        assert_eq!(q.variance(1.0), uniform);
        assert_eq!(q.variance(res / 0.01), uniform);
        let slow = res / 0.01 / 25.0;
        assert!((q.variance(slow) / uniform - 25.0).abs() < 1e-12);
        assert!(q.variance(0.0).is_finite() && q.variance(0.0) >= 1e8 * uniform);
        let noisy = SuspensionNoise {
            variance: 1e-6,
            ..q
        };
        assert!((noisy.variance(slow) - 25.0 * uniform - 1e-6).abs() < 1e-18);
    }
}
