//! Dead reckoning, the estimator a rover team builds without a model of
//! the rover: the attitude from the gyros, corrected towards the
//! accelerometers' gravity by a complementary filter on SO(3) (Mahony,
//! Hamel and Pflimlin, "Nonlinear complementary filters on the special
//! orthogonal group", IEEE Trans. Automatic Control 53(5), 2008, with its
//! gyro-bias integral), and the position from the wheel encoders' mean
//! rolling speed, along the body's x axis, projected with that attitude.
//! The suspension is read from its encoders.
//!
//! It is the baseline the model-based filter is measured against: the
//! same sensor log, nothing else. Where the wheels skid (a slip-steered
//! turn) or slip (soft soil) its distance and heading drift, because
//! rolling is all it knows of how the rover moves.

use alloc::vec;
use alloc::vec::Vec;

use crate::sensors::{SensorConfig, SensorSample};
use rover_dynamics::linalg::{M3, cross, mat_mul, mul, mul_t};

use crate::rotation::{euler, exp, orthonormalize, rotation};

/// The complementary filter's gains.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DeadReckoningConfig {
    /// Proportional gain of the gravity correction \[1/s\]: the attitude
    /// follows the accelerometers with the time constant `1/kp`.
    pub kp: f64,
    /// Integral gain \[1/s²\]: how fast the gyro-bias estimate follows the
    /// persistent part of the correction.
    pub ki: f64,
    /// The correction is skipped while the specific force's magnitude
    /// differs from gravity by more than this fraction: the rover is then
    /// accelerating and the accelerometers do not point up.
    pub accel_gate: f64,
}

impl Default for DeadReckoningConfig {
    /// Gains for a slow rover and a MEMS IMU: a 10 s time constant (the
    /// rover's accelerations over rough ground average out), and a bias
    /// integral ten times slower.
    fn default() -> Self {
        Self {
            kp: 0.1,
            ki: 0.001,
            accel_gate: 0.05,
        }
    }
}

/// Why dead reckoning cannot take a sample.
#[derive(Clone, Debug, PartialEq)]
pub enum DeadReckoningError {
    /// The sensors declared do not include what it needs.
    Missing(&'static str),
    /// A sample's reading is not finite, or its time does not advance.
    BadSample {
        /// Time of the sample \[s\].
        t: f64,
        /// What is wrong.
        what: &'static str,
    },
    /// The sample's sizes do not match the rover.
    Size {
        /// Which reading.
        what: &'static str,
        /// Entries expected.
        expected: usize,
        /// Entries found.
        found: usize,
    },
}

impl core::fmt::Display for DeadReckoningError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            Self::Missing(what) => write!(
                f,
                "dead reckoning needs {what}: declare it in the scenario's [sensors] table"
            ),
            Self::BadSample { t, what } => write!(f, "sensor sample at t = {t} s: {what}"),
            Self::Size {
                what,
                expected,
                found,
            } => write!(f, "{what}: {found} entries, the rover has {expected}"),
        }
    }
}

impl core::error::Error for DeadReckoningError {}

/// The dead-reckoning estimate, advanced one sensor sample at a time.
/// Allocates nothing after [`DeadReckoning::new`].
#[derive(Clone, Debug)]
pub struct DeadReckoning {
    config: DeadReckoningConfig,
    /// Body → inertial.
    r: M3<f64>,
    /// IMU axes → body (the transpose of the mounting's body → IMU).
    imu_to_body: M3<f64>,
    gyro_bias: [f64; 3],
    position: [f64; 3],
    /// Speed along the body's x axis \[m/s\].
    speed: f64,
    /// Angular velocity, bias removed, body components \[rad/s\].
    omega: [f64; 3],
    radii: Vec<f64>,
    gravity: f64,
    t: f64,
    last_angles: Vec<f64>,
    suspension: Vec<f64>,
    suspension_rates: Vec<f64>,
}

impl DeadReckoning {
    /// Starts at time `t0` from the known pose `x0 = [X, Y, Z, φ, θ, ψ,
    /// y1 … ym]` (docs/MODEL.md §2), at rest. `radii` are the wheels'
    /// radii \[m\]; `gravity` is the planet's \[m/s²\]. The sensors must
    /// include an IMU and wheel encoders.
    pub fn new(
        config: DeadReckoningConfig,
        sensors: &SensorConfig,
        radii: &[f64],
        gravity: f64,
        t0: f64,
        x0: &[f64],
    ) -> Result<Self, DeadReckoningError> {
        let imu = sensors
            .imu
            .as_ref()
            .ok_or(DeadReckoningError::Missing("an IMU"))?;
        if sensors.wheel_encoders.is_none() {
            return Err(DeadReckoningError::Missing("wheel encoders"));
        }
        let [f, t, p] = imu.orientation_deg.map(f64::to_radians);
        let m = x0.len().saturating_sub(6);
        Ok(Self {
            config,
            r: rotation(&x0[3..6]),
            // The mounting's angles give the IMU's axes in body components.
            imu_to_body: rotation(&[f, t, p]),
            gyro_bias: [0.0; 3],
            position: [x0[0], x0[1], x0[2]],
            speed: 0.0,
            omega: [0.0; 3],
            radii: radii.to_vec(),
            gravity,
            t: t0,
            // An encoder reads the wheel's rotation since the start.
            last_angles: vec![0.0; radii.len()],
            suspension: x0[6..].to_vec(),
            suspension_rates: vec![0.0; m],
        })
    }

    /// Takes one sample: the attitude advances over the interval since the
    /// last with the gyros and turns towards the accelerometers' vertical,
    /// the position with the wheels' mean rolling speed over it. On error
    /// the estimate is left as it was.
    pub fn update(&mut self, s: &SensorSample) -> Result<(), DeadReckoningError> {
        self.check(s)?;
        let (Some(gyro), Some(accel)) = (s.gyro, s.accel) else {
            return Err(DeadReckoningError::BadSample {
                t: s.t,
                what: "no IMU reading",
            });
        };
        let dt = s.t - self.t;
        let gyro = mul(&self.imu_to_body, gyro);
        let accel = mul(&self.imu_to_body, accel);
        // The accelerometers' up against the estimate's, in body axes.
        let mut correction = [0.0; 3];
        let norm = libm::sqrt(accel.iter().map(|a| a * a).sum::<f64>());
        if (norm - self.gravity).abs() <= self.config.accel_gate * self.gravity && norm > 0.0 {
            let measured = accel.map(|a| a / norm);
            let estimated = mul_t(&self.r, [0.0, 0.0, 1.0]);
            correction = cross(measured, estimated);
        }
        for i in 0..3 {
            self.gyro_bias[i] -= self.config.ki * correction[i] * dt;
            self.omega[i] = gyro[i] - self.gyro_bias[i];
        }
        let turn: [f64; 3] =
            core::array::from_fn(|i| (self.omega[i] + self.config.kp * correction[i]) * dt);
        // The position advances along the heading at mid-interval.
        let half = mat_mul(&self.r, &exp(turn.map(|a| 0.5 * a)));
        self.r = orthonormalize(&mat_mul(&self.r, &exp(turn)));
        self.speed = self.rolling_speed(&s.wheel_angles, dt);
        let step = mul(&half, [self.speed * dt, 0.0, 0.0]);
        for (p, d) in self.position.iter_mut().zip(step) {
            *p += d;
        }
        for ((y, rate), z) in self
            .suspension
            .iter_mut()
            .zip(&mut self.suspension_rates)
            .zip(&s.suspension)
        {
            *rate = (z - *y) / dt;
            *y = *z;
        }
        self.last_angles.copy_from_slice(&s.wheel_angles);
        self.t = s.t;
        Ok(())
    }

    /// The wheels' mean rolling speed over the interval: each encoder's
    /// turn over it times the wheel's radius.
    fn rolling_speed(&self, angles: &[f64], dt: f64) -> f64 {
        let sum: f64 = angles
            .iter()
            .zip(&self.last_angles)
            .zip(&self.radii)
            .map(|((a, b), r)| (a - b) * r)
            .sum();
        sum / (dt * self.radii.len() as f64)
    }

    fn check(&self, s: &SensorSample) -> Result<(), DeadReckoningError> {
        let bad = |what| Err(DeadReckoningError::BadSample { t: s.t, what });
        if s.t.partial_cmp(&self.t) != Some(core::cmp::Ordering::Greater) {
            return bad("its time does not advance");
        }
        if s.wheel_angles.len() != self.radii.len() {
            return Err(DeadReckoningError::Size {
                what: "wheel encoders",
                expected: self.radii.len(),
                found: s.wheel_angles.len(),
            });
        }
        if !s.suspension.is_empty() && s.suspension.len() != self.suspension.len() {
            return Err(DeadReckoningError::Size {
                what: "suspension encoders",
                expected: self.suspension.len(),
                found: s.suspension.len(),
            });
        }
        let finite = |v: &[f64]| v.iter().all(|a| a.is_finite());
        let imu_finite = s.gyro.is_none_or(|g| finite(&g)) && s.accel.is_none_or(|a| finite(&a));
        if !imu_finite || !finite(&s.wheel_angles) || !finite(&s.suspension) {
            return bad("a reading is not finite");
        }
        Ok(())
    }

    /// Time of the last sample taken \[s\].
    pub fn time(&self) -> f64 {
        self.t
    }

    /// The estimate in the model's layout (docs/MODEL.md §2):
    /// `x = [X, Y, Z, φ, θ, ψ, y1 … ym]` and `w = [vx, vy, vz, Ωx, Ωy, Ωz,
    /// ẏ1 … ẏm]`, the velocity the rolling speed along the body's x axis.
    pub fn state(&self, x: &mut [f64], w: &mut [f64]) {
        x[..3].copy_from_slice(&self.position);
        x[3..6].copy_from_slice(&euler(&self.r, 0.0));
        x[6..].copy_from_slice(&self.suspension);
        w[..3].copy_from_slice(&[self.speed, 0.0, 0.0]);
        w[3..6].copy_from_slice(&self.omega);
        w[6..].copy_from_slice(&self.suspension_rates);
    }

    /// The gyro-bias estimate, body components \[rad/s\].
    pub fn gyro_bias(&self) -> [f64; 3] {
        self.gyro_bias
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sensors::{EncoderConfig, ImuConfig};

    const G: f64 = 3.71;
    const RADIUS: f64 = 0.1;

    fn sensors() -> SensorConfig {
        SensorConfig {
            seed: 0,
            rate: 100.0,
            imu: Some(ImuConfig {
                gyro_noise_deg_per_sqrt_h: 0.0,
                gyro_bias_deg_per_h: 0.0,
                accel_noise_ug_per_sqrt_hz: 0.0,
                accel_bias_mg: 0.0,
                bias_time: 300.0,
                position: [0.0; 3],
                orientation_deg: [0.0; 3],
            }),
            wheel_encoders: Some(EncoderConfig { resolution: 1e-9 }),
            suspension_encoders: None,
            position_fix: None,
            heading_fix: None,
        }
    }

    /// A level rover on flat ground turning at `yaw_rate` with its wheels
    /// rolling at `speed`, read perfectly (plus a gyro bias `bias`) every
    /// 10 ms for `seconds`, taken by a dead reckoning started at `x0`.
    fn drive(x0: &[f64], speed: f64, yaw_rate: f64, bias: [f64; 3], seconds: f64) -> DeadReckoning {
        let mut dr = DeadReckoning::new(
            DeadReckoningConfig::default(),
            &sensors(),
            &[RADIUS; 4],
            G,
            0.0,
            x0,
        )
        .unwrap();
        let steps = (seconds * 100.0).round() as usize;
        for k in 1..=steps {
            let t = k as f64 * 0.01;
            let sample = SensorSample {
                t,
                gyro: Some([bias[0], bias[1], yaw_rate + bias[2]]),
                accel: Some([0.0, 0.0, G]),
                wheel_angles: vec![speed * t / RADIUS; 4],
                ..SensorSample::default()
            };
            dr.update(&sample).unwrap();
        }
        dr
    }

    fn state(dr: &DeadReckoning) -> (Vec<f64>, Vec<f64>) {
        let (mut x, mut w) = (vec![0.0; 6], vec![0.0; 6]);
        dr.state(&mut x, &mut w);
        (x, w)
    }

    #[test]
    fn straight_line_along_the_heading() {
        let psi = 0.6;
        let dr = drive(&[1.0, 2.0, 0.3, 0.0, 0.0, psi], 0.05, 0.0, [0.0; 3], 20.0);
        let (x, w) = state(&dr);
        // 20 s of rolling at 5 cm/s from the first interval on.
        let d = 0.05 * 20.0;
        assert!((x[0] - (1.0 + d * psi.cos())).abs() < 1e-9, "{x:?}");
        assert!((x[1] - (2.0 + d * psi.sin())).abs() < 1e-9, "{x:?}");
        assert!((x[2] - 0.3).abs() < 1e-12 && (w[0] - 0.05).abs() < 1e-12);
    }

    #[test]
    fn a_full_circle_closes() {
        // One turn in 40 s at 5 cm/s: a circle of radius V/ψ̇.
        let rate = core::f64::consts::TAU / 40.0;
        let dr = drive(&[0.0; 6], 0.05, rate, [0.0; 3], 40.0);
        let (x, _) = state(&dr);
        // The midpoint rule's error over a turn, O(dt²), is far below this.
        assert!(x[0].hypot(x[1]) < 1e-5, "{x:?}");
        assert!(x[5].abs() < 1e-9, "{x:?}");
    }

    #[test]
    fn roll_and_pitch_turn_to_the_accelerometers_and_the_bias_is_learnt() {
        // Started 5° off in roll and pitch, with a roll-gyro bias of 10 °/h:
        // the bias integral's slow pole, (kp − √(kp² − 4ki))/2 = 0.011/s,
        // leaves e^-13 of the start after 1200 s: the attitude is the
        // accelerometers' and the integral holds the bias.
        let bias = (10.0f64 / 3600.0).to_radians();
        let dr = drive(
            &[0.0, 0.0, 0.0, 5f64.to_radians(), -5f64.to_radians(), 0.0],
            0.0,
            0.0,
            [bias, 0.0, 0.0],
            1200.0,
        );
        let (x, _) = state(&dr);
        assert!(
            x[3].abs() < 1e-3f64.to_radians(),
            "roll {}",
            x[3].to_degrees()
        );
        assert!(
            x[4].abs() < 1e-3f64.to_radians(),
            "pitch {}",
            x[4].to_degrees()
        );
        assert!(
            (dr.gyro_bias()[0] - bias).abs() < 0.01 * bias,
            "{:?}",
            dr.gyro_bias()
        );
    }

    #[test]
    fn bad_samples_are_refused_and_leave_the_estimate() {
        let mut dr = drive(&[0.0; 6], 0.05, 0.0, [0.0; 3], 1.0);
        let before = state(&dr);
        let t = dr.time();
        let mut s = SensorSample {
            t: t + 0.01,
            gyro: Some([f64::NAN, 0.0, 0.0]),
            accel: Some([0.0, 0.0, G]),
            wheel_angles: vec![0.0; 4],
            ..SensorSample::default()
        };
        assert!(matches!(
            dr.update(&s),
            Err(DeadReckoningError::BadSample { .. })
        ));
        s.gyro = Some([0.0; 3]);
        s.wheel_angles = vec![0.0; 3];
        assert!(matches!(
            dr.update(&s),
            Err(DeadReckoningError::Size { .. })
        ));
        s.wheel_angles = vec![0.0; 4];
        s.t = t;
        assert!(dr.update(&s).is_err());
        assert_eq!(state(&dr), before);
    }
}
