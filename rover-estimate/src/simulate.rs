//! What the sensors of a [`SensorConfig`] read when the rover's motion is
//! known: the truth at one sensor instant ([`Truth`]) becomes one
//! [`SensorSample`], with seeded noise ([`SensorSimulator`]). The models
//! (the repository's `docs/ESTIMATE.md`, "Sensors", gives them with their
//! units):
//!
//! ```text
//! gyro   = C·Ω + b_g + n_g
//! accel  = C·(a_P − g_body) + b_a + n_a
//! a_P    = (v̇ + Ω×v) + Ω̇×r + Ω×(Ω×r)       body components
//! g_body = −g·Rᵀ·e_Z                        gravity in body components
//! n ~ N(0, density²·rate)                   white noise, per axis
//! b_{k+1} = e^{−Δt/τ}·b_k + σ·√(1 − e^{−2Δt/τ})·η,   b_0 ~ N(0, σ²)
//! enc_j  = round(θ_j / res)·res,  θ_j = ∫ ω_j dt (trapezoid between samples)
//! susp_i = round((y_i + n) / res)·res,  n ~ N(0, noise²)
//! fix    = [X, Y, Z] + N(0, σ²) per axis;   ψ + N(0, σ²)
//! ```
//!
//! C turns body axes into the IMU's (the transpose of `Rz(ψ)·Rx(φ)·Ry(θ)`
//! of `orientation_deg`, docs/MODEL.md §1's order), r is the IMU's
//! `position` from G in body axes, v and Ω are the body-component velocity
//! of G and angular velocity (docs/MODEL.md §2), and R the body's attitude.
//! A level rover at rest reads `accel = (0, 0, +g)`.
//!
//! Every noise draws from its own stream, seeded from the declaration's
//! `seed` and the stream's name: the same seed gives the same readings bit
//! for bit, and declaring another sensor leaves the others' noise as it
//! was.
//!
//! ```
//! use rover_estimate::sensors::{ImuConfig, SensorConfig};
//! use rover_estimate::{SensorSimulator, Truth};
//!
//! // A perfect IMU at G on a level rover at rest on Mars.
//! let imu = ImuConfig {
//!     gyro_noise_deg_per_sqrt_h: 0.0,
//!     gyro_bias_deg_per_h: 0.0,
//!     accel_noise_ug_per_sqrt_hz: 0.0,
//!     accel_bias_mg: 0.0,
//!     bias_time: 300.0,
//!     position: [0.0; 3],
//!     orientation_deg: [0.0; 3],
//! };
//! let config = SensorConfig {
//!     seed: 1,
//!     rate: 100.0,
//!     imu: Some(imu),
//!     wheel_encoders: None,
//!     suspension_encoders: None,
//!     position_fix: None,
//!     heading_fix: None,
//! };
//! let mut sim = SensorSimulator::new(&config, 4, 4)?;
//! let mut sample = sim.new_sample();
//! let rest = [0.0; 10];
//! let truth = Truth {
//!     t: 0.0,
//!     x: &rest,
//!     w: &rest,
//!     w_dot: &rest,
//!     wheel_rates: &[0.0; 4],
//!     torques: &[0.0; 4],
//!     steering: &[0.0; 4],
//!     gravity: 3.71,
//! };
//! sim.sample_into(&truth, &mut sample)?;
//! assert_eq!(sample.accel, Some([0.0, 0.0, 3.71]));
//! assert_eq!(sample.gyro, Some([0.0; 3]));
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

use rand_core::SeedableRng;
use rand_distr::{Distribution, StandardNormal};
use rand_pcg::Pcg64;
use rover_dynamics::attitude::Attitude;
use rover_dynamics::linalg::{M3, add, cross, mul_t};

use crate::sensors::{SensorConfig, SensorSample};

/// The rover's motion at one sensor instant, as the simulation knows it.
#[derive(Clone, Copy, Debug)]
pub struct Truth<'a> {
    /// Time \[s\].
    pub t: f64,
    /// The coordinates `x = [X, Y, Z, φ, θ, ψ, y1…ym]` (docs/MODEL.md §2).
    pub x: &'a [f64],
    /// The pseudo-velocities `w = [vx, vy, vz, Ωx, Ωy, Ωz, ẏ1…ẏm]`, v and Ω
    /// in body components.
    pub w: &'a [f64],
    /// Their rates `ẇ`, from the right-hand side at this instant.
    pub w_dot: &'a [f64],
    /// Each wheel's spin rate \[rad/s\], positive rolling forwards.
    pub wheel_rates: &'a [f64],
    /// The motor torques in force [N·m], one per wheel.
    pub torques: &'a [f64],
    /// The steering angles in force \[rad\], one per wheel.
    pub steering: &'a [f64],
    /// Gravity's magnitude [m/s²] (the rover description's; it points
    /// along −Z).
    pub gravity: f64,
}

/// A [`Truth`] that does not fit the simulator, or comes out of order.
#[derive(Clone, Debug, PartialEq)]
pub enum SampleError {
    /// A slice of the truth of the wrong length.
    Length {
        /// Which slice (`x`, `w`, `w_dot`, `wheel_rates`, `torques`,
        /// `steering`).
        what: &'static str,
        /// The length the simulator was built for.
        expected: usize,
        /// The truth's.
        got: usize,
    },
    /// A time not after the previous sample's, or not finite.
    Time {
        /// The truth's time \[s\].
        t: f64,
        /// The previous sample's \[s\].
        previous: f64,
    },
}

impl core::fmt::Display for SampleError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            SampleError::Length {
                what,
                expected,
                got,
            } => write!(
                f,
                "the truth's `{what}` has {got} values, the sensors were built for {expected}"
            ),
            SampleError::Time { t, previous } => write!(
                f,
                "a sensor sample at t = {t} s does not follow the previous one at t = {previous} s: samples come in increasing time"
            ),
        }
    }
}

impl core::error::Error for SampleError {}

/// The noise streams, one per sensor and kind: declaring a sensor draws
/// from its streams only.
mod stream {
    pub const GYRO_NOISE: u64 = 1;
    pub const GYRO_BIAS: u64 = 2;
    pub const ACCEL_NOISE: u64 = 3;
    pub const ACCEL_BIAS: u64 = 4;
    pub const SUSPENSION: u64 = 5;
    pub const POSITION: u64 = 6;
    pub const HEADING: u64 = 7;
}

/// SplitMix64's finalizer (Steele, Lea & Flood, OOPSLA 2014): a bijection
/// of u64 that spreads neighbouring seeds far apart.
fn splitmix64(mut z: u64) -> u64 {
    z = z.wrapping_add(0x9e37_79b9_7f4a_7c15);
    z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
    z ^ (z >> 31)
}

/// The generator of stream `id` for `seed`: PCG64 (O'Neill 2014) seeded
/// from both through SplitMix64, so that streams differ in their state
/// and their increment alike.
fn generator(seed: u64, id: u64) -> Pcg64 {
    Pcg64::seed_from_u64(splitmix64(seed ^ splitmix64(id)))
}

/// One draw of N(0, 1).
fn normal(rng: &mut Pcg64) -> f64 {
    StandardNormal.sample(rng)
}

/// `v` to the nearest multiple of `resolution` (half away from zero): the
/// count of an encoder whose zero lies half a count from the start, so
/// that the error is uniform in ±resolution/2, zero-mean, of variance
/// resolution²/12. (Truncating to the count below, `floor`, would add a
/// bias of −resolution/2.)
fn quantize(v: f64, resolution: f64) -> f64 {
    // + 0.0 turns the count −0 into 0.
    libm::round(v / resolution) * resolution + 0.0
}

/// A first-order Gauss–Markov bias per axis, with its white noise.
#[derive(Clone, Debug)]
struct NoisyAxes {
    /// White noise's standard deviation per sample, density·√rate.
    white: f64,
    /// The bias's stationary standard deviation.
    sigma: f64,
    /// Its correlation time \[s\].
    tau: f64,
    bias: [f64; 3],
    noise_rng: Pcg64,
    bias_rng: Pcg64,
}

impl NoisyAxes {
    fn new(seed: u64, (noise_id, bias_id): (u64, u64), white: f64, sigma: f64, tau: f64) -> Self {
        Self {
            white,
            sigma,
            tau,
            bias: [0.0; 3],
            noise_rng: generator(seed, noise_id),
            bias_rng: generator(seed, bias_id),
        }
    }

    /// The bias at the first sample, drawn from its stationary law.
    fn start(&mut self) {
        for b in &mut self.bias {
            *b = self.sigma * normal(&mut self.bias_rng);
        }
    }

    /// The bias `dt` later: the exact discretization of
    /// `ḃ = −b/τ + √(2σ²/τ)·ξ`, which keeps its variance σ² at any step.
    fn wander(&mut self, dt: f64) {
        let phi = libm::exp(-dt / self.tau);
        let kick = self.sigma * libm::sqrt((1.0 - phi * phi).max(0.0));
        for b in &mut self.bias {
            *b = phi * *b + kick * normal(&mut self.bias_rng);
        }
    }

    /// `v` plus the bias and a draw of white noise.
    fn read(&mut self, v: [f64; 3]) -> [f64; 3] {
        let mut out = add(v, self.bias);
        for o in &mut out {
            *o += self.white * normal(&mut self.noise_rng);
        }
        out
    }
}

/// The IMU's fixed geometry and its noise.
#[derive(Clone, Debug)]
struct Imu {
    /// `Rz(ψ)·Rx(φ)·Ry(θ)` of `orientation_deg`: IMU axes → body axes
    /// (its transpose is C).
    axes: M3<f64>,
    /// The IMU's origin from G, body axes \[m\].
    lever: [f64; 3],
    gyro: NoisyAxes,
    accel: NoisyAxes,
}

/// A sparse fix: due at the first sensor instant at or after each multiple
/// of its period, counted from t = 0.
#[derive(Clone, Debug)]
struct Fix {
    period: f64,
    sigma: f64,
    /// The next fix is due at `next · period`.
    next: u64,
    rng: Pcg64,
}

impl Fix {
    fn new(seed: u64, id: u64, rate: f64, sigma: f64) -> Self {
        Self {
            period: 1.0 / rate,
            sigma,
            next: 0,
            rng: generator(seed, id),
        }
    }

    /// Whether a fix is due at `t`; if so, the next one is counted from the
    /// multiple after `t`.
    fn due(&mut self, t: f64) -> bool {
        // Sensor instants meet the multiples of the period to rounding.
        let slack = 1e-9 * (1.0 + libm::fabs(t));
        if t + slack < self.next as f64 * self.period {
            return false;
        }
        self.next = libm::floor((t + slack) / self.period) as u64 + 1;
        true
    }

    /// `truth` with its noise when a fix is due at `t`.
    fn read<const N: usize>(&mut self, t: f64, truth: [f64; N]) -> Option<[f64; N]> {
        if !self.due(t) {
            return None;
        }
        let (sigma, rng) = (self.sigma, &mut self.rng);
        Some(truth.map(|v| v + sigma * normal(rng)))
    }
}

/// The sensors of one declaration on one rover, turning truths into
/// readings (see the module's documentation for the models).
///
/// Built once ([`SensorSimulator::new`]), then fed the truth at each sensor
/// instant in increasing time ([`SensorSimulator::sample_into`]): that
/// allocates nothing. The wheel encoders integrate each wheel's spin rate
/// between samples, so the simulator is fed every instant of the run, the
/// first at t = 0.
#[derive(Clone, Debug)]
pub struct SensorSimulator {
    config: SensorConfig,
    wheels: usize,
    coordinates: usize,
    imu: Option<Imu>,
    /// Each wheel's rotation since the start, unquantized \[rad\].
    angles: alloc::vec::Vec<f64>,
    /// Each wheel's spin rate at the previous sample \[rad/s\].
    rates: alloc::vec::Vec<f64>,
    suspension_rng: Pcg64,
    position: Option<Fix>,
    heading: Option<Fix>,
    /// The previous sample's time, `None` before the first.
    previous: Option<f64>,
}

impl SensorSimulator {
    /// The sensors of `config` ([`SensorConfig::check`]ed) on a rover of
    /// `wheels` wheels and `coordinates` suspension coordinates.
    pub fn new(
        config: &SensorConfig,
        wheels: usize,
        coordinates: usize,
    ) -> Result<Self, crate::sensors::InvalidSensor> {
        config.check()?;
        let seed = config.seed;
        let sqrt_rate = libm::sqrt(config.rate);
        let imu = config.imu.as_ref().map(|c| {
            let [roll, pitch, yaw] = c.orientation_deg.map(f64::to_radians);
            Imu {
                axes: Attitude::new(roll, pitch, yaw).rotation(),
                lever: c.position,
                gyro: NoisyAxes::new(
                    seed,
                    (stream::GYRO_NOISE, stream::GYRO_BIAS),
                    c.gyro_noise_density() * sqrt_rate,
                    c.gyro_bias_sigma(),
                    c.bias_time,
                ),
                accel: NoisyAxes::new(
                    seed,
                    (stream::ACCEL_NOISE, stream::ACCEL_BIAS),
                    c.accel_noise_density() * sqrt_rate,
                    c.accel_bias_sigma(),
                    c.bias_time,
                ),
            }
        });
        let fix = |id, rate, sigma| Fix::new(seed, id, rate, sigma);
        Ok(Self {
            imu,
            angles: alloc::vec![0.0; wheels],
            rates: alloc::vec![0.0; wheels],
            suspension_rng: generator(seed, stream::SUSPENSION),
            position: config
                .position_fix
                .as_ref()
                .map(|f| fix(stream::POSITION, f.rate, f.sigma)),
            heading: config
                .heading_fix
                .as_ref()
                .map(|f| fix(stream::HEADING, f.rate, f.sigma)),
            previous: None,
            config: config.clone(),
            wheels,
            coordinates,
        })
    }

    /// The declaration.
    pub fn config(&self) -> &SensorConfig {
        &self.config
    }

    /// A sample of this simulator's shape, for [`SensorSimulator::sample_into`].
    pub fn new_sample(&self) -> SensorSample {
        SensorSample::sized(&self.config, self.wheels, self.coordinates)
    }

    /// Back to before the first sample: the same seed's noise from its
    /// start, the encoders at zero.
    pub fn reset(&mut self) {
        if let Ok(fresh) = Self::new(&self.config, self.wheels, self.coordinates) {
            *self = fresh;
        }
    }

    /// The readings of `truth` into `out` (a sample of
    /// [`SensorSimulator::new_sample`]'s shape; another is resized, which
    /// allocates once). Allocates nothing otherwise.
    pub fn sample_into(
        &mut self,
        truth: &Truth<'_>,
        out: &mut SensorSample,
    ) -> Result<(), SampleError> {
        self.check(truth)?;
        let n = 6 + self.coordinates;
        let (x, w, w_dot) = (&truth.x[..n], &truth.w[..n], &truth.w_dot[..n]);
        let dt = self.previous.map(|p| truth.t - p);
        out.t = truth.t;
        // IMU.
        match &mut self.imu {
            Some(imu) => {
                match dt {
                    None => {
                        imu.gyro.start();
                        imu.accel.start();
                    }
                    Some(dt) => {
                        imu.gyro.wander(dt);
                        imu.accel.wander(dt);
                    }
                }
                let v = [w[0], w[1], w[2]];
                let omega = [w[3], w[4], w[5]];
                let v_dot = [w_dot[0], w_dot[1], w_dot[2]];
                let omega_dot = [w_dot[3], w_dot[4], w_dot[5]];
                let r = imu.lever;
                // a_P = (v̇ + Ω×v) + Ω̇×r + Ω×(Ω×r), body components.
                let a_g = add(v_dot, cross(omega, v));
                let a_p = add(a_g, add(cross(omega_dot, r), cross(omega, cross(omega, r))));
                // a_P − g_body, g_body = −g·Rᵀe_Z.
                let up = Attitude::new(x[3], x[4], x[5]).up_in_body();
                let specific = add(a_p, up.map(|u| truth.gravity * u));
                out.gyro = Some(imu.gyro.read(mul_t(&imu.axes, omega)));
                out.accel = Some(imu.accel.read(mul_t(&imu.axes, specific)));
            }
            None => {
                out.gyro = None;
                out.accel = None;
            }
        }
        // Wheel encoders: the rotation by the trapezoid rule.
        if let Some(dt) = dt {
            for ((a, r0), r1) in self
                .angles
                .iter_mut()
                .zip(&self.rates)
                .zip(truth.wheel_rates)
            {
                *a += 0.5 * (r0 + r1) * dt;
            }
        }
        self.rates.copy_from_slice(truth.wheel_rates);
        match &self.config.wheel_encoders {
            Some(e) => {
                out.wheel_angles.resize(self.wheels, 0.0);
                for (o, a) in out.wheel_angles.iter_mut().zip(&self.angles) {
                    *o = quantize(*a, e.resolution);
                }
            }
            None => out.wheel_angles.clear(),
        }
        // Suspension encoders.
        match &self.config.suspension_encoders {
            Some(e) => {
                out.suspension.resize(self.coordinates, 0.0);
                for (o, y) in out.suspension.iter_mut().zip(&x[6..n]) {
                    let noise = if e.noise > 0.0 {
                        e.noise * normal(&mut self.suspension_rng)
                    } else {
                        0.0
                    };
                    *o = quantize(y + noise, e.resolution);
                }
            }
            None => out.suspension.clear(),
        }
        // Fixes.
        let t = truth.t;
        out.position = self
            .position
            .as_mut()
            .and_then(|f| f.read(t, [x[0], x[1], x[2]]));
        out.heading = self
            .heading
            .as_mut()
            .and_then(|f| f.read(t, [x[5]]))
            .map(|[psi]| psi);
        // Commands.
        out.torques.resize(self.wheels, 0.0);
        out.torques.copy_from_slice(truth.torques);
        out.steering.resize(self.wheels, 0.0);
        out.steering.copy_from_slice(truth.steering);
        self.previous = Some(truth.t);
        Ok(())
    }

    /// The truth's lengths and time.
    fn check(&self, truth: &Truth<'_>) -> Result<(), SampleError> {
        let n = 6 + self.coordinates;
        let k = self.wheels;
        let lengths = [
            ("x", truth.x.len(), n),
            ("w", truth.w.len(), n),
            ("w_dot", truth.w_dot.len(), n),
            ("wheel_rates", truth.wheel_rates.len(), k),
            ("torques", truth.torques.len(), k),
            ("steering", truth.steering.len(), k),
        ];
        // x, w and ẇ may carry more (a state's controller integrals and
        // spins after them).
        for (what, got, expected) in lengths {
            let short = got < expected;
            let per_wheel = matches!(what, "wheel_rates" | "torques" | "steering");
            if short || (per_wheel && got != expected) {
                return Err(SampleError::Length {
                    what,
                    expected,
                    got,
                });
            }
        }
        let previous = self.previous.unwrap_or(f64::NEG_INFINITY);
        if !(truth.t.is_finite() && truth.t > previous) {
            return Err(SampleError::Time {
                t: truth.t,
                previous,
            });
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    extern crate std;

    use super::*;
    use crate::sensors::{
        EncoderConfig, HeadingFixConfig, ImuConfig, PositionFixConfig, STANDARD_GRAVITY,
        SuspensionEncoderConfig,
    };
    use alloc::string::ToString;
    use alloc::vec;
    use alloc::vec::Vec;

    fn imu(gyro_noise: f64, gyro_bias: f64, accel_noise: f64, accel_bias: f64) -> ImuConfig {
        ImuConfig {
            gyro_noise_deg_per_sqrt_h: gyro_noise,
            gyro_bias_deg_per_h: gyro_bias,
            accel_noise_ug_per_sqrt_hz: accel_noise,
            accel_bias_mg: accel_bias,
            bias_time: 300.0,
            position: [0.0; 3],
            orientation_deg: [0.0; 3],
        }
    }

    fn config(imu: Option<ImuConfig>) -> SensorConfig {
        SensorConfig {
            seed: 7,
            rate: 100.0,
            imu,
            wheel_encoders: None,
            suspension_encoders: None,
            position_fix: None,
            heading_fix: None,
        }
    }

    /// A rover of 4 wheels and 2 suspension coordinates: its state now.
    struct State {
        x: [f64; 8],
        w: [f64; 8],
        w_dot: [f64; 8],
        rates: [f64; 4],
        commands: [f64; 4],
        gravity: f64,
    }

    impl State {
        fn at_rest(gravity: f64) -> Self {
            State {
                x: [0.0; 8],
                w: [0.0; 8],
                w_dot: [0.0; 8],
                rates: [0.0; 4],
                commands: [0.0; 4],
                gravity,
            }
        }
        fn truth(&self, t: f64) -> Truth<'_> {
            Truth {
                t,
                x: &self.x,
                w: &self.w,
                w_dot: &self.w_dot,
                wheel_rates: &self.rates,
                torques: &self.commands,
                steering: &self.commands,
                gravity: self.gravity,
            }
        }
    }

    /// `count` samples of `config` at its rate with the rover as `state`.
    fn samples(config: &SensorConfig, state: &State, count: usize) -> Vec<SensorSample> {
        let mut sim = SensorSimulator::new(config, 4, 2).unwrap();
        let mut s = sim.new_sample();
        (0..count)
            .map(|k| {
                sim.sample_into(&state.truth(k as f64 / config.rate), &mut s)
                    .unwrap();
                s.clone()
            })
            .collect()
    }

    fn mean_and_std(v: impl Iterator<Item = f64> + Clone) -> (f64, f64) {
        let n = v.clone().count() as f64;
        let mean = v.clone().sum::<f64>() / n;
        let var = v.map(|x| (x - mean) * (x - mean)).sum::<f64>() / (n - 1.0);
        (mean, var.sqrt())
    }

    #[test]
    fn a_level_rover_at_rest_reads_plus_g_up_and_no_rate() {
        let c = config(Some(imu(0.0, 0.0, 0.0, 0.0)));
        let s = &samples(&c, &State::at_rest(3.71), 3)[2];
        assert_eq!(s.gyro, Some([0.0; 3]));
        assert_eq!(s.accel, Some([0.0, 0.0, 3.71]));
        // Tilted: the IMU reads g·Rᵀe_Z, the vertical in body axes.
        let mut tilted = State::at_rest(9.81);
        let (phi, theta) = (0.2_f64, -0.3_f64);
        tilted.x[3] = phi;
        tilted.x[4] = theta;
        tilted.x[5] = 1.0;
        let a = samples(&c, &tilted, 1)[0].accel.unwrap();
        let want = [
            -9.81 * phi.cos() * theta.sin(),
            9.81 * phi.sin(),
            9.81 * phi.cos() * theta.cos(),
        ];
        for k in 0..3 {
            assert!((a[k] - want[k]).abs() < 1e-14, "{a:?} {want:?}");
        }
    }

    #[test]
    fn the_lever_arm_adds_the_centripetal_and_tangential_accelerations() {
        // A body turning about z at ω, speeding its turn up at α, G moving
        // forward at u and accelerating at u̇; the IMU at r = (l, 0, 0) with
        // its axes turned 90° about z (its x is the body's y), no gravity.
        let (omega, alpha, u, u_dot, l) = (0.7, 0.3, 0.2, 0.05, 0.4);
        let mut c = config(Some(imu(0.0, 0.0, 0.0, 0.0)));
        if let Some(i) = &mut c.imu {
            i.position = [l, 0.0, 0.0];
            i.orientation_deg = [0.0, 0.0, 90.0];
        }
        let mut s = State::at_rest(0.0);
        s.w[0] = u;
        s.w[5] = omega;
        s.w_dot[0] = u_dot;
        s.w_dot[5] = alpha;
        let read = &samples(&c, &s, 1)[0];
        // Body components: v̇ + Ω×v = (u̇, ω·u, 0); Ω̇×r = (0, α·l, 0);
        // Ω×(Ω×r) = (−ω²·l, 0, 0).
        let body = [u_dot - omega * omega * l, omega * u + alpha * l, 0.0];
        // In the IMU's axes (x_imu = y_body, y_imu = −x_body).
        let want = [body[1], -body[0], body[2]];
        let a = read.accel.unwrap();
        let g = read.gyro.unwrap();
        for k in 0..3 {
            assert!((a[k] - want[k]).abs() < 1e-15, "{a:?} {want:?}");
        }
        assert!(g[0].abs() < 1e-16 && g[1].abs() < 1e-16 && (g[2] - omega).abs() < 1e-16);
    }

    #[test]
    fn white_noise_has_the_datasheet_density_times_the_root_of_the_rate() {
        // 0.2 °/√h and 100 µg/√Hz at 100 Hz, no bias.
        let c = config(Some(imu(0.2, 0.0, 100.0, 0.0)));
        let n = 20_000;
        let s = samples(&c, &State::at_rest(1.62), n);
        let gyro_sigma = 0.2_f64.to_radians() / 60.0 * 10.0;
        let accel_sigma = 100e-6 * STANDARD_GRAVITY * 10.0;
        // A sample standard deviation of n normal draws is off by
        // σ/√(2n) (0.5 % here) in one standard error: 5 of them bound it.
        let se = 1.0 / (2.0 * n as f64).sqrt();
        for k in 0..3 {
            let (mean, std) = mean_and_std(s.iter().map(|s| s.gyro.unwrap()[k]));
            assert!(
                (std / gyro_sigma - 1.0).abs() < 5.0 * se,
                "gyro {k}: {std} vs {gyro_sigma}"
            );
            assert!(
                mean.abs() < 5.0 * gyro_sigma / (n as f64).sqrt(),
                "gyro {k} mean {mean}"
            );
            let offset = if k == 2 { 1.62 } else { 0.0 };
            let (mean, std) = mean_and_std(s.iter().map(|s| s.accel.unwrap()[k] - offset));
            assert!(
                (std / accel_sigma - 1.0).abs() < 5.0 * se,
                "accel {k}: {std} vs {accel_sigma}"
            );
            assert!(
                mean.abs() < 5.0 * accel_sigma / (n as f64).sqrt(),
                "accel {k} mean {mean}"
            );
        }
        // The axes' noises are independent: their correlation is within
        // 5/√n of 0.
        let xs: Vec<f64> = s.iter().map(|s| s.gyro.unwrap()[0]).collect();
        let ys: Vec<f64> = s.iter().map(|s| s.gyro.unwrap()[1]).collect();
        let r = xs.iter().zip(&ys).map(|(a, b)| a * b).sum::<f64>()
            / (xs.iter().map(|a| a * a).sum::<f64>() * ys.iter().map(|b| b * b).sum::<f64>())
                .sqrt();
        assert!(r.abs() < 5.0 / (n as f64).sqrt(), "{r}");
    }

    #[test]
    fn the_bias_wanders_with_its_stationary_sigma_and_correlation_time() {
        // Sampled at 1 Hz with τ = 1 s, so that the samples are nearly
        // independent (lag-1 correlation e^-1) and a long run measures
        // the law closely; no white noise.
        let mut c = config(Some(imu(0.0, 36.0, 0.0, 2.0)));
        c.rate = 1.0;
        if let Some(i) = &mut c.imu {
            i.bias_time = 1.0;
        }
        let sigma = c.imu.as_ref().unwrap().gyro_bias_sigma();
        let n = 50_000;
        let s = samples(&c, &State::at_rest(0.0), n);
        let phi = (-1.0_f64).exp();
        // For an AR(1) series of lag-1 correlation φ the sample variance's
        // relative standard error is √(2(1+φ²)/((1−φ²)·n)) (0.7 % here),
        // the standard deviation's half that; a lag correlation's is
        // about √((1−φ^2)/n) (0.4 %). Five standard errors bound each.
        let std_se = 0.5 * (2.0 * (1.0 + phi * phi) / ((1.0 - phi * phi) * n as f64)).sqrt();
        let corr_se = ((1.0 - phi * phi) / n as f64).sqrt();
        for k in 0..3 {
            let b: Vec<f64> = s.iter().map(|s| s.gyro.unwrap()[k]).collect();
            let (mean, std) = mean_and_std(b.iter().copied());
            assert!(
                (std / sigma - 1.0).abs() < 5.0 * std_se,
                "axis {k}: {std} vs {sigma}"
            );
            assert!(mean.abs() < 5.0 * sigma * ((1.0 + phi) / ((1.0 - phi) * n as f64)).sqrt());
            for lag in [1usize, 2, 3] {
                let r = b
                    .iter()
                    .zip(&b[lag..])
                    .map(|(a, c)| (a - mean) * (c - mean))
                    .sum::<f64>()
                    / ((n - lag) as f64 * std * std);
                let want = phi.powi(lag as i32);
                assert!(
                    (r - want).abs() < 5.0 * corr_se,
                    "axis {k} lag {lag}: {r} vs {want}"
                );
            }
        }
        // The accelerometers' bias, in mg.
        let sigma = 2e-3 * STANDARD_GRAVITY;
        let (_, std) = mean_and_std(s.iter().map(|s| s.accel.unwrap()[1]));
        assert!((std / sigma - 1.0).abs() < 5.0 * std_se, "{std} vs {sigma}");
        // The first bias is drawn from the stationary law: over 4000 seeds
        // its standard deviation is σ within 5 standard errors (1.1 %).
        let first: Vec<f64> = (0..4000)
            .map(|seed| {
                c.seed = seed;
                samples(&c, &State::at_rest(0.0), 1)[0].gyro.unwrap()[0]
            })
            .collect();
        let sigma = c.imu.as_ref().unwrap().gyro_bias_sigma();
        let (_, std) = mean_and_std(first.iter().copied());
        assert!(
            (std / sigma - 1.0).abs() < 5.0 / (2.0 * 4000.0_f64).sqrt(),
            "{std} vs {sigma}"
        );
    }

    #[test]
    fn the_encoders_integrate_each_wheels_rate_to_within_the_rule_and_a_count() {
        let mut c = config(None);
        c.wheel_encoders = Some(EncoderConfig { resolution: 1e-3 });
        let mut sim = SensorSimulator::new(&c, 4, 2).unwrap();
        let mut out = sim.new_sample();
        let mut s = State::at_rest(0.0);
        // ω_j(t) = (j+1)·(2 + sin t) − 1: θ_j(t) = (j+1)·(2t + 1 − cos t) − t.
        let h = 0.01;
        for k in 0..=1000 {
            let t = k as f64 * h;
            for j in 0..4 {
                s.rates[j] = (j as f64 + 1.0) * (2.0 + t.sin()) - 1.0;
            }
            sim.sample_into(&s.truth(t), &mut out).unwrap();
            for j in 0..4 {
                let exact = (j as f64 + 1.0) * (2.0 * t + 1.0 - t.cos()) - t;
                // The trapezoid's error: t·h²/12·max|ω''| ≤ 4·t·h²/12.
                let rule = 4.0 * t * h * h / 12.0;
                let err = (out.wheel_angles[j] - exact).abs();
                assert!(err <= 0.5e-3 + rule + 1e-12, "wheel {j} at {t}: {err}");
                // A whole number of counts.
                let counts = out.wheel_angles[j] / 1e-3;
                assert!((counts - counts.round()).abs() < 1e-6);
            }
        }
    }

    #[test]
    fn the_suspension_encoders_read_each_coordinate_with_noise_and_counts() {
        let mut c = config(None);
        let resolution = 0.1_f64.to_radians();
        c.suspension_encoders = Some(SuspensionEncoderConfig {
            resolution,
            noise: 0.0,
        });
        let mut s = State::at_rest(0.0);
        s.x[6] = 0.3;
        s.x[7] = -0.123_45;
        let read = samples(&c, &s, 1)[0].suspension.clone();
        assert_eq!(
            read,
            vec![(0.3 / resolution).round() * resolution, -71.0 * resolution]
        );
        // With noise far above a count, the readings scatter by the noise.
        c.suspension_encoders = Some(SuspensionEncoderConfig {
            resolution: 1e-6,
            noise: 0.01,
        });
        let n = 20_000;
        let (mean, std) = mean_and_std(samples(&c, &s, n).iter().map(|r| r.suspension[1]));
        // The rounding adds (1e-6)²/12 to the variance: nothing here.
        assert!(
            (std / 0.01 - 1.0).abs() < 5.0 / (2.0 * n as f64).sqrt(),
            "{std}"
        );
        assert!(
            (mean - s.x[7]).abs() < 5.0 * 0.01 / (n as f64).sqrt(),
            "{mean}"
        );
    }

    #[test]
    fn fixes_come_at_their_own_rates_counted_from_the_start() {
        let mut c = config(None);
        c.position_fix = Some(PositionFixConfig {
            rate: 2.0,
            sigma: 0.05,
        });
        // 0.3 Hz: every 3.33… s, at the first sensor instant after.
        c.heading_fix = Some(HeadingFixConfig {
            rate: 0.3,
            sigma: 0.01,
        });
        let mut s = State::at_rest(0.0);
        s.x[0] = 5.0;
        s.x[5] = 0.4;
        let run = samples(&c, &s, 1001);
        let at = |f: &dyn Fn(&SensorSample) -> bool| -> Vec<usize> {
            run.iter()
                .enumerate()
                .filter(|(_, r)| f(r))
                .map(|(k, _)| k)
                .collect()
        };
        let position: Vec<usize> = at(&|r| r.position.is_some());
        assert_eq!(position, (0..=1000).step_by(50).collect::<Vec<_>>());
        assert_eq!(at(&|r| r.heading.is_some()), vec![0, 334, 667, 1000]);
        let p = run[50].position.unwrap();
        assert!(p != [5.0, 0.0, 0.0] && (p[0] - 5.0).abs() < 5.0 * 0.05);
        // Fixes add no other reading.
        assert!(
            run.iter()
                .all(|r| r.gyro.is_none() && r.wheel_angles.is_empty())
        );
    }

    #[test]
    fn the_same_seed_gives_the_same_bits_and_another_sensor_leaves_the_imus_noise_alone() {
        let mut c = config(Some(imu(0.2, 10.0, 100.0, 0.1)));
        c.suspension_encoders = Some(SuspensionEncoderConfig {
            resolution: 1e-4,
            noise: 1e-3,
        });
        let s = State::at_rest(1.62);
        let bits = |r: &[SensorSample]| -> Vec<u64> {
            r.iter()
                .flat_map(|r| {
                    r.gyro
                        .unwrap()
                        .into_iter()
                        .chain(r.accel.unwrap())
                        .chain(r.suspension.iter().copied())
                })
                .map(f64::to_bits)
                .collect()
        };
        let a = samples(&c, &s, 200);
        assert_eq!(bits(&a), bits(&samples(&c, &s, 200)));
        // Another seed: every reading differs.
        let mut other = c.clone();
        other.seed = 8;
        let b = samples(&other, &s, 200);
        let imu_bits = |r: &[SensorSample]| -> Vec<u64> {
            r.iter()
                .flat_map(|r| r.gyro.unwrap().into_iter().chain(r.accel.unwrap()))
                .map(f64::to_bits)
                .collect()
        };
        let same = imu_bits(&a)
            .iter()
            .zip(imu_bits(&b))
            .filter(|(x, y)| **x == *y)
            .count();
        assert_eq!(same, 0);
        // The suspension's (counts of 1e-4 under a noise of 1e-3) meet
        // now and then, by chance.
        let differ = a
            .iter()
            .zip(&b)
            .filter(|(x, y)| x.suspension != y.suspension)
            .count();
        assert!(differ > 190, "{differ}");
        // A fix and encoders declared besides: the IMU reads as before.
        let mut more = c.clone();
        more.position_fix = Some(PositionFixConfig {
            rate: 1.0,
            sigma: 0.1,
        });
        more.wheel_encoders = Some(EncoderConfig { resolution: 1e-3 });
        let m = samples(&more, &s, 200);
        assert_eq!(bits(&a), bits(&m));
        // A reset starts the same noise again.
        let mut sim = SensorSimulator::new(&c, 4, 2).unwrap();
        let mut out = sim.new_sample();
        for k in 0..3 {
            sim.sample_into(&s.truth(k as f64 * 0.01), &mut out)
                .unwrap();
        }
        sim.reset();
        sim.sample_into(&s.truth(0.0), &mut out).unwrap();
        assert_eq!(out, a[0]);
    }

    #[test]
    fn a_truth_of_another_shape_or_out_of_order_is_refused() {
        let c = config(Some(imu(0.2, 10.0, 100.0, 0.1)));
        let mut sim = SensorSimulator::new(&c, 4, 2).unwrap();
        let mut out = sim.new_sample();
        let s = State::at_rest(1.62);
        let mut t = s.truth(0.0);
        t.torques = &s.rates[..3];
        assert_eq!(
            sim.sample_into(&t, &mut out),
            Err(SampleError::Length {
                what: "torques",
                expected: 4,
                got: 3
            })
        );
        sim.sample_into(&s.truth(0.5), &mut out).unwrap();
        let e = sim.sample_into(&s.truth(0.5), &mut out).unwrap_err();
        assert_eq!(
            e.to_string(),
            "a sensor sample at t = 0.5 s does not follow the previous one at t = 0.5 s: samples come in increasing time"
        );
    }
}
