//! The model-based extended Kalman filter: the rover's own model
//! ([`ProcessModel`]) predicts, its sensors ([`SensorConfig`]) correct.
//!
//! An error-state filter (docs/ESTIMATE.md, "The filter"):
//! - the **nominal state** is the model's `y = [x; w; ω]`, Euler angles as
//!   the model keeps them, then the IMU's gyro and accelerometer biases
//!   when there is an IMU;
//! - the **error state** is `δy` with the attitude's three entries
//!   replaced by a small rotation δθ in inertial axes,
//!   `R_true = exp(δθ×)·R_est`: its covariance never meets the Euler
//!   singularity, and a correction turns the attitude (`R ← exp(δθ×)·R`,
//!   the angles read back) rather than adding to the angles;
//! - a **prediction** takes a linearly implicit Euler step on the
//!   model's assembled Jacobian (the tyres make the model stiff: an
//!   explicit 10 ms step is unstable) and carries the covariance with the
//!   same step's transition;
//! - an **update** linearizes a sensor's readings at the estimate and
//!   takes them one scalar at a time (their noises are uncorrelated).
//!
//! Every buffer is sized in [`Estimator::new`]: a step allocates nothing.

mod config;
mod dense;
mod error;
mod measure;
mod noise;
mod predict;
mod state_sigma;
mod step_matrix;
mod update;

use alloc::vec;
use alloc::vec::Vec;

pub use config::{FilterConfig, InitialSigma};
pub use error::EstimateError;

use crate::process::ProcessModel;
use crate::sensors::{SensorConfig, SensorSample};
use noise::SensorNoise;
use step_matrix::StepMatrix;

/// Where the attitude lies in `x` (and δθ in the error state).
const ATTITUDE: core::ops::Range<usize> = 3..6;

/// The filter's result type.
pub type Result<T, E> = core::result::Result<T, EstimateError<E>>;

/// The model-based error-state extended Kalman filter over a process
/// model `M` (module docs).
#[derive(Clone, Debug)]
pub struct Estimator<M: ProcessModel> {
    model: M,
    layout: Layout,
    config: FilterConfig,
    noise: SensorNoise,
    /// Each error component's process-noise density² (`q²` of
    /// [`FilterConfig`]), the biases' left 0 (their Gauss–Markov noise is
    /// discrete).
    process_noise: Vec<f64>,
    estimate: Snapshot,
    /// The estimate before the call in progress, restored when it fails.
    saved: Snapshot,
    linearization: Linearization,
    /// The prediction's `I − h·J`, factored.
    step: StepMatrix,
    work: Work,
}

/// Sizes and places in the state.
#[derive(Clone, Copy, Debug)]
struct Layout {
    /// Generalized coordinates N.
    n: usize,
    /// The model's state length.
    dim: usize,
    /// The error state's length: `dim`, plus 6 biases with an IMU.
    len: usize,
    wheels: usize,
    /// The IMU's biases follow the model's error state.
    imu: bool,
}

impl Layout {
    /// The gyro bias's first index in the error state.
    fn gyro_bias(&self) -> usize {
        self.dim
    }
    /// The accelerometer bias's first index.
    fn accel_bias(&self) -> usize {
        self.dim + 3
    }
}

/// What a failed call must leave as it found: the estimate and the
/// encoders' memory.
#[derive(Clone, Debug)]
struct Snapshot {
    t: f64,
    /// The model's state.
    y: Vec<f64>,
    /// Gyro bias \[rad/s\], then accelerometer bias [m/s²] (IMU axes).
    bias: [f64; 6],
    /// The error state's covariance, row-major `len × len`.
    p: Vec<f64>,
    /// Each wheel's last angle and when it was read.
    wheel_angles: Vec<f64>,
    wheel_angles_t: Option<f64>,
    /// The torques the last prediction held, and how much each changed
    /// from the one before (0 at the first).
    torques: Vec<f64>,
    torque_change: Vec<f64>,
    /// Bumped by every change of `y`: the linearization's key.
    version: u64,
}

impl Snapshot {
    fn copy_from(&mut self, other: &Snapshot) {
        self.t = other.t;
        self.y.copy_from_slice(&other.y);
        self.bias = other.bias;
        self.p.copy_from_slice(&other.p);
        self.wheel_angles.copy_from_slice(&other.wheel_angles);
        self.wheel_angles_t = other.wheel_angles_t;
        self.torques.copy_from_slice(&other.torques);
        self.torque_change.copy_from_slice(&other.torque_change);
        self.version = other.version;
    }
}

/// The model's right-hand side `f` at the estimate of `f_at` (time and
/// version), and a Jacobian taken at `jacobian_at`, `jacobian_age`
/// predictions ago.
///
/// An update that needs them (the accelerometers) takes them at the
/// prior; the next prediction starts from that Jacobian (taken at its
/// time, before the correction) and a fresh right-hand side, so that a
/// filter step costs one Jacobian. With [`FilterConfig::jacobian_every`]
/// above 1 a Jacobian serves that many predictions.
#[derive(Clone, Debug)]
struct Linearization {
    f: Vec<f64>,
    jac: Vec<f64>,
    f_at: Option<(f64, u64)>,
    jacobian_at: Option<(f64, u64)>,
    jacobian_age: Option<usize>,
    /// The response to each wheel's torque, `b_k = ∂f/∂τ_k` in row `k`
    /// (`wheels × dim`), for [`FilterConfig::torque_sigma`], and how many
    /// predictions ago it was taken.
    torque_response: Vec<f64>,
    torque_response_age: Option<usize>,
}

impl Linearization {
    /// The Jacobian may serve one more prediction.
    fn jacobian_current(&self, every: usize) -> bool {
        self.jacobian_age.is_some_and(|age| age < every)
    }

    /// Nothing in the buffers is trusted any more.
    fn forget(&mut self) {
        self.f_at = None;
        self.jacobian_at = None;
        self.jacobian_age = None;
        self.torque_response_age = None;
    }

    /// Both were just evaluated at `key`.
    fn taken(&mut self, key: (f64, u64)) {
        self.f_at = Some(key);
        self.jacobian_at = Some(key);
        self.jacobian_age = Some(0);
    }
}

/// Scratch buffers.
#[derive(Clone, Debug)]
struct Work {
    /// A step's right-hand side, then its increment.
    step: Vec<f64>,
    /// A measurement's row `H` in error coordinates.
    row: Vec<f64>,
    /// A sensor's three rows (the IMU's axes), `3 × len`.
    rows: Vec<f64>,
    /// `P·Hᵀ`.
    gain: Vec<f64>,
    /// The correction accumulated over one sensor's scalar updates.
    correction: Vec<f64>,
    /// The nonzero entries of `H`.
    nonzero: Vec<usize>,
    /// Each wheel's model rate and its gradient (`wheels × dim`).
    rates: Vec<f64>,
    rate_gradient: Vec<f64>,
    /// The pose and velocity block of `P`, factored, for the NEES.
    block: Vec<f64>,
    deviation: Vec<f64>,
    /// The commanded torques with one of them nudged, and the right-hand
    /// side under them, for `∂f/∂τ`.
    nudged_torques: Vec<f64>,
    nudged_rhs: Vec<f64>,
}

impl<M: ProcessModel> Estimator<M> {
    /// A filter over `model`, its sensors declared by `sensors`, tuned by
    /// `config`, started at time `t0` from the state `y0` (the model's
    /// layout) with the standard deviations `initial` (uncorrelated); the
    /// IMU's biases start at zero with their datasheet σ.
    pub fn new(
        model: M,
        sensors: &SensorConfig,
        config: FilterConfig,
        t0: f64,
        y0: &[f64],
        initial: &InitialSigma,
    ) -> Result<Self, M::Error> {
        let layout = layout(&model)?;
        let noise = SensorNoise::new(sensors)?;
        config.validate()?;
        initial.validate()?;
        if !t0.is_finite() {
            return Err(EstimateError::Config {
                field: "t0",
                value: t0,
                expected: "finite",
            });
        }
        let gravity = model.gravity();
        config::check("the process model's gravity", gravity, false)?;
        check_len("y0", layout.dim, y0.len())?;
        check_finite(t0, "y0", y0)?;
        let layout = Layout {
            imu: noise.imu.is_some(),
            len: layout.dim + if noise.imu.is_some() { 6 } else { 0 },
            ..layout
        };
        let process_noise = process_noise(&layout, &config, model.spin_range());
        let p = initial_covariance(&layout, initial, &noise, model.spin_range());
        let estimate = Snapshot {
            t: t0,
            y: y0.to_vec(),
            bias: [0.0; 6],
            p,
            wheel_angles: vec![0.0; layout.wheels],
            wheel_angles_t: None,
            torques: vec![f64::NAN; layout.wheels],
            torque_change: vec![0.0; layout.wheels],
            version: 0,
        };
        let (dim, len) = (layout.dim, layout.len);
        Ok(Self {
            model,
            layout,
            config,
            noise,
            process_noise,
            saved: estimate.clone(),
            estimate,
            linearization: Linearization {
                f: vec![0.0; dim],
                jac: vec![0.0; dim * dim],
                f_at: None,
                jacobian_at: None,
                jacobian_age: None,
                torque_response: vec![0.0; layout.wheels * dim],
                torque_response_age: None,
            },
            step: StepMatrix::new(layout.n, dim, len),
            work: Work {
                step: vec![0.0; dim],
                row: vec![0.0; len],
                rows: vec![0.0; 3 * len],
                gain: vec![0.0; len],
                correction: vec![0.0; len],
                nonzero: vec![0; len],
                rates: vec![0.0; layout.wheels],
                rate_gradient: vec![0.0; layout.wheels * dim],
                block: vec![0.0; 4 * layout.n * layout.n],
                deviation: vec![0.0; dim],
                nudged_torques: vec![0.0; layout.wheels],
                nudged_rhs: vec![0.0; dim],
            },
        })
    }

    /// The estimate's time \[s\].
    pub fn time(&self) -> f64 {
        self.estimate.t
    }

    /// The estimated model state `y = [x; w; ω]`.
    pub fn state(&self) -> &[f64] {
        &self.estimate.y
    }

    /// The estimated gyro bias \[rad/s\] and accelerometer bias [m/s²],
    /// in the IMU's axes, when there is an IMU.
    pub fn biases(&self) -> Option<([f64; 3], [f64; 3])> {
        let b = &self.estimate.bias;
        self.layout
            .imu
            .then(|| ([b[0], b[1], b[2]], [b[3], b[4], b[5]]))
    }

    /// Length of the error state: the model's `dim` (the attitude as δθ),
    /// plus the two biases' 6 with an IMU.
    pub fn error_dim(&self) -> usize {
        self.layout.len
    }

    /// The error state's covariance, row-major `error_dim × error_dim`.
    pub fn covariance(&self) -> &[f64] {
        &self.estimate.p
    }

    /// One standard deviation per error-state component into `out`
    /// (`error_dim` long): position \[m\], δθ \[rad\], suspension, velocity,
    /// angular velocity, suspension rates, spins, then the biases.
    pub fn sigma(&self, out: &mut [f64]) -> Result<(), M::Error> {
        let len = self.layout.len;
        check_len("sigma", len, out.len())?;
        for (i, o) in out.iter_mut().enumerate() {
            *o = libm::sqrt(self.estimate.p[i * len + i]);
        }
        Ok(())
    }

    /// The process model.
    pub fn model(&self) -> &M {
        &self.model
    }

    /// The process model, to change what it holds between steps (its
    /// terrain map, say); the filter's state is its own.
    pub fn model_mut(&mut self) -> &mut M {
        &mut self.model
    }

    /// The tuning.
    pub fn config(&self) -> &FilterConfig {
        &self.config
    }

    /// The wheels' normal loads \[N\] and longitudinal slips (0 on rigid
    /// ground) at the estimate, into `normal` and `slip` (one per wheel):
    /// what the model says the ground does, which no sensor reads.
    pub fn wheel_outputs(&mut self, normal: &mut [f64], slip: &mut [f64]) -> Result<(), M::Error> {
        let wheels = self.layout.wheels;
        check_len("normal", wheels, normal.len())?;
        check_len("slip", wheels, slip.len())?;
        let t = self.estimate.t;
        self.model
            .rhs(t, &self.estimate.y, &mut self.work.step)
            .map_err(|source| EstimateError::Model { t, source })?;
        self.model.wheel_outputs(normal, slip);
        Ok(())
    }

    /// The normalized estimation error squared over the pose and the
    /// velocities (the 2N entries of `[x; w]`, the attitude's as the
    /// small rotation from the estimate to `truth`):
    /// `εᵀ·P_xw⁻¹·ε`, chi-square with 2N degrees of freedom when the
    /// filter is consistent. `truth` is a model state (`dim` long).
    pub fn nees(&mut self, truth: &[f64]) -> Result<f64, M::Error> {
        let Layout { n, len, .. } = self.layout;
        let t = self.estimate.t;
        let mut deviation = core::mem::take(&mut self.work.deviation);
        let result = self.deviation(truth, &mut deviation);
        self.work.deviation = deviation;
        result?;
        let deviation = &mut self.work.deviation;
        let m = 2 * n;
        let block = &mut self.work.block;
        for i in 0..m {
            block[i * m..(i + 1) * m].copy_from_slice(&self.estimate.p[i * len..i * len + m]);
        }
        dense::cholesky(block, m).map_err(|k| EstimateError::NotPositiveDefinite {
            t,
            what: "pose and velocity covariance pivot",
            index: k,
            value: block[k * m + k],
        })?;
        Ok(dense::cholesky_quadratic(block, m, deviation))
    }

    /// Applies every reading of `sample` (at the estimate's time): the
    /// IMU, the wheel encoders, the suspension encoders, the fixes. All or
    /// nothing: when one fails, none is applied.
    pub fn update(&mut self, sample: &SensorSample) -> Result<(), M::Error> {
        let t = self.estimate.t;
        if !sample.t.is_finite() || (sample.t - t).abs() > 1e-9 * t.abs().max(1.0) {
            return Err(EstimateError::Time {
                t,
                sample: sample.t,
            });
        }
        self.guarded(|s| {
            if sample.gyro.is_some() || sample.accel.is_some() {
                s.imu(sample.gyro, sample.accel)?;
            }
            if !sample.wheel_angles.is_empty() {
                s.wheel_angles(&sample.wheel_angles)?;
            }
            if !sample.suspension.is_empty() {
                s.suspension(&sample.suspension)?;
            }
            if let Some(p) = sample.position {
                s.position(p)?;
            }
            if let Some(h) = sample.heading {
                s.heading(h)?;
            }
            Ok(())
        })
    }

    /// The IMU's readings at the estimate's time: gyros \[rad/s\] and
    /// accelerometers (specific force, [m/s²]) in the IMU's axes; either
    /// may be absent.
    pub fn update_imu(
        &mut self,
        gyro: Option<[f64; 3]>,
        accel: Option<[f64; 3]>,
    ) -> Result<(), M::Error> {
        self.guarded(|s| s.imu(gyro, accel))
    }

    /// Each wheel's angle since the start \[rad\], read at the estimate's
    /// time: the rate over the interval since the last reading is
    /// compared with the model's (the first reading is only remembered).
    pub fn update_wheel_angles(&mut self, angles: &[f64]) -> Result<(), M::Error> {
        self.guarded(|s| s.wheel_angles(angles))
    }

    /// Each suspension coordinate (rad, or m).
    pub fn update_suspension(&mut self, values: &[f64]) -> Result<(), M::Error> {
        self.guarded(|s| s.suspension(values))
    }

    /// A fix of G's position, inertial \[m\].
    pub fn update_position(&mut self, position: [f64; 3]) -> Result<(), M::Error> {
        self.guarded(|s| s.position(position))
    }

    /// A fix of the yaw ψ \[rad\] (any turn: the innovation is wrapped).
    pub fn update_heading(&mut self, heading: f64) -> Result<(), M::Error> {
        self.guarded(|s| s.heading(heading))
    }

    /// Runs `call`; when it fails, the estimate is put back as it was.
    fn guarded(
        &mut self,
        call: impl FnOnce(&mut Self) -> Result<(), M::Error>,
    ) -> Result<(), M::Error> {
        self.saved.copy_from(&self.estimate);
        let result = call(self);
        if result.is_err() {
            self.estimate.copy_from(&self.saved);
            // The buffers may hold a failed call's evaluations.
            self.linearization.forget();
        }
        result
    }
}

/// The model's sizes, its state checked to be `[x; w; ω]`.
fn layout<M: ProcessModel>(model: &M) -> Result<Layout, M::Error> {
    let (n, dim, spins) = (model.dof(), model.dim(), model.spin_range());
    if n < 6 || dim != 2 * n + spins.len() || (!spins.is_empty() && spins != (2 * n..dim)) {
        return Err(EstimateError::Layout {
            dim,
            dof: n,
            spins: spins.len(),
        });
    }
    Ok(Layout {
        n,
        dim,
        len: dim,
        wheels: model.wheel_count(),
        imu: false,
    })
}

/// Each error component's process-noise density².
fn process_noise(
    layout: &Layout,
    config: &FilterConfig,
    spins: core::ops::Range<usize>,
) -> Vec<f64> {
    let c = config;
    let sigma = [
        c.position_noise,
        c.attitude_noise,
        c.suspension_noise,
        c.velocity_noise,
        c.angular_velocity_noise,
        c.suspension_rate_noise,
        c.spin_noise,
    ];
    by_group(layout, sigma.map(|s| s * s), spins)
}

/// One value per error component from one per group — position,
/// attitude, suspension, velocity, angular velocity, suspension rates,
/// spins — the biases' left 0.
fn by_group(layout: &Layout, values: [f64; 7], spins: core::ops::Range<usize>) -> Vec<f64> {
    let n = layout.n;
    let mut out = vec![0.0; layout.len];
    let ranges = [
        0..3,
        ATTITUDE,
        6..n,
        n..n + 3,
        n + 3..n + 6,
        n + 6..2 * n,
        spins,
    ];
    for (range, v) in ranges.into_iter().zip(values) {
        out[range].iter_mut().for_each(|o| *o = v);
    }
    out
}

/// The initial covariance: diagonal, from `initial` and the biases' σ.
fn initial_covariance(
    layout: &Layout,
    initial: &InitialSigma,
    noise: &SensorNoise,
    spins: core::ops::Range<usize>,
) -> Vec<f64> {
    let len = layout.len;
    let i = initial;
    let groups = [
        i.position,
        i.attitude,
        i.suspension,
        i.velocity,
        i.angular_velocity,
        i.suspension_rate,
        i.spin,
    ];
    let mut sigma = by_group(layout, groups, spins);
    if let Some(imu) = &noise.imu {
        let g = layout.gyro_bias();
        sigma[g..g + 3]
            .iter_mut()
            .for_each(|v| *v = imu.gyro_bias_sigma);
        let a = layout.accel_bias();
        sigma[a..a + 3]
            .iter_mut()
            .for_each(|v| *v = imu.accel_bias_sigma);
    }
    let mut p = vec![0.0; len * len];
    for (i, s) in sigma.iter().enumerate() {
        p[i * len + i] = s * s;
    }
    p
}

/// `given == expected`, else a length error.
fn check_len<E>(what: &'static str, expected: usize, given: usize) -> Result<(), E> {
    if given == expected {
        Ok(())
    } else {
        Err(EstimateError::Length {
            what,
            expected,
            given,
        })
    }
}

/// Every value finite, else the first that is not.
fn check_finite<E>(t: f64, what: &'static str, values: &[f64]) -> Result<(), E> {
    match values.iter().position(|v| !v.is_finite()) {
        Some(index) => Err(EstimateError::NotFinite {
            t,
            what,
            index,
            value: values[index],
        }),
        None => Ok(()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sensors::PositionFixConfig;

    /// A body drifting at constant velocity: `ẋ = w`, `ẇ = 0`.
    struct Drift;

    impl ProcessModel for Drift {
        type Error = &'static str;
        fn dof(&self) -> usize {
            6
        }
        fn dim(&self) -> usize {
            12
        }
        fn wheel_count(&self) -> usize {
            0
        }
        fn spin_range(&self) -> core::ops::Range<usize> {
            12..12
        }
        fn gravity(&self) -> f64 {
            0.0
        }
        fn set_inputs(&mut self, _: &[f64], _: &[f64]) -> core::result::Result<(), &'static str> {
            Ok(())
        }
        fn rhs(
            &mut self,
            _: f64,
            y: &[f64],
            dy: &mut [f64],
        ) -> core::result::Result<(), &'static str> {
            dy[..6].copy_from_slice(&y[6..]);
            dy[6..].fill(0.0);
            Ok(())
        }
        fn rhs_and_jacobian(
            &mut self,
            t: f64,
            y: &[f64],
            dy: &mut [f64],
            jac: &mut [f64],
        ) -> core::result::Result<(), &'static str> {
            jac.fill(0.0);
            (0..6).for_each(|i| jac[i * 12 + 6 + i] = 1.0);
            self.rhs(t, y, dy)
        }
        fn wheel_rates(
            &mut self,
            _: f64,
            _: &[f64],
            _: &mut [f64],
            _: &mut [f64],
        ) -> core::result::Result<(), &'static str> {
            Ok(())
        }
        fn wheel_outputs(&self, _: &mut [f64], _: &mut [f64]) {}
    }

    fn drift() -> Estimator<Drift> {
        let sensors = SensorConfig {
            seed: 0,
            rate: 100.0,
            imu: None,
            wheel_encoders: None,
            suspension_encoders: None,
            position_fix: Some(PositionFixConfig {
                rate: 1.0,
                sigma: 0.1,
            }),
            heading_fix: None,
        };
        let y0 = [0.0; 12];
        Estimator::new(
            Drift,
            &sensors,
            FilterConfig::default(),
            0.0,
            &y0,
            // 1 cm and 10 mrad throughout: variances of 1e-4, which the
            // tests below drive negative on purpose.
            &InitialSigma {
                position: 0.01,
                attitude: 0.01,
                ..InitialSigma::default()
            },
        )
        .unwrap()
    }

    /// A covariance that lost definiteness (a negative variance of X, as
    /// rounding could leave it) is caught at the first reading of X, at
    /// its time, and the estimate is left as it was.
    #[test]
    fn a_covariance_that_lost_definiteness_is_an_error() {
        let mut filter = drift();
        filter.estimate.p[0] = -1.0;
        let before = filter.estimate.clone();
        let e = filter.update_position([0.5, 0.0, 0.0]).unwrap_err();
        assert_eq!(
            e,
            EstimateError::NotPositiveDefinite {
                t: 0.0,
                what: "position fix innovation variance, axis",
                index: 0,
                value: -1.0 + 0.01,
            }
        );
        assert_eq!(filter.estimate.p, before.p);
        assert_eq!(filter.estimate.y, before.y);
        // A negative variance of a component the fix does not read shows
        // after the prediction.
        filter.estimate.p[0] = before.p[13];
        filter.estimate.p[13 * 7] = -1.0;
        let e = filter.predict(0.01, &[], &[]).unwrap_err();
        assert!(
            matches!(
                e,
                EstimateError::NotPositiveDefinite {
                    what: "covariance diagonal after a prediction, component",
                    index: 7,
                    ..
                }
            ),
            "{e:?}"
        );
        assert_eq!(filter.time(), 0.0);
    }
}
