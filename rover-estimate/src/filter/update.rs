//! The updates: each sensor's readings linearized once at the estimate,
//! then taken one scalar at a time (their noises are uncorrelated), the
//! corrections accumulated in the error state and injected at the end.
//!
//! For one scalar reading `z` of variance `r` and row `H` (error
//! coordinates), with `δ` the correction so far:
//! ```text
//! u = P·Hᵀ,   s = H·u + r,   ν = z − h(ŷ) − H·δ
//! δ ← δ + u·ν/s,   P ← P − u·uᵀ/s
//! ```
//! (`P − u·uᵀ/s` is the Joseph form's value at the optimal gain, and
//! stays exactly symmetric); each costs O(len²). Taking a sensor's rows in
//! turn this way equals the batch update linearized at the prior.

use rover_dynamics::linalg::{mat_mul, transpose};

use super::measure::{self, to_error_coordinates};
use super::{ATTITUDE, EstimateError, Estimator, Result, check_finite, check_len};
use crate::process::ProcessModel;
use crate::rotation::{self, error_map, wrap};

impl<M: ProcessModel> Estimator<M> {
    /// The model's right-hand side at the estimate, unless it is there,
    /// and a Jacobian as `need` says.
    fn linearize_here(&mut self, need: Need) -> Result<(), M::Error> {
        let key = (self.estimate.t, self.estimate.version);
        let lin = &mut self.linearization;
        let current = match need {
            Need::Rhs => true,
            Need::Current => lin.jacobian_current(self.config.jacobian_every),
            Need::Exact => lin.jacobian_at == Some(key),
        };
        if lin.f_at == Some(key) && current {
            return Ok(());
        }
        let model_error = |source| EstimateError::Model { t: key.0, source };
        if current {
            self.model
                .rhs(key.0, &self.estimate.y, &mut lin.f)
                .map_err(model_error)?;
            lin.f_at = Some(key);
        } else {
            self.model
                .rhs_and_jacobian(key.0, &self.estimate.y, &mut lin.f, &mut lin.jac)
                .map_err(model_error)?;
            lin.taken(key);
        }
        Ok(())
    }

    /// The readings the IMU should give at the estimate, gyros then
    /// accelerometers (IMU axes, biases included), and, when `rows` is
    /// given (`6 × error_dim`), their gradients against the error state,
    /// on the model's Jacobian at the estimate.
    pub fn predicted_imu(&mut self, rows: Option<&mut [f64]>) -> Result<[f64; 6], M::Error> {
        let t = self.estimate.t;
        let Some(imu) = self.noise.imu else {
            return Err(EstimateError::NoSensor { t, sensor: "imu" });
        };
        let len = self.layout.len;
        let mut own = [0.0; 0];
        let rows: &mut [f64] = match rows {
            Some(r) => {
                check_len("rows", 6 * len, r.len())?;
                r
            }
            None => &mut own,
        };
        self.linearize_here(if rows.is_empty() {
            Need::Rhs
        } else {
            Need::Exact
        })?;
        let y = &self.estimate.y;
        let (_, t_inv) = error_map(&y[ATTITUDE]);
        let scratch = &mut self.work.rows;
        let g = measure::gyro(&self.layout, y, &self.estimate.bias, &imu, scratch);
        if !rows.is_empty() {
            rows[..3 * len].copy_from_slice(&scratch[..3 * len]);
        }
        let lin = &self.linearization;
        let a = measure::accelerometer(
            &self.layout,
            (y, &lin.f, &lin.jac),
            &self.estimate.bias,
            &imu,
            self.model.gravity(),
            &t_inv,
            scratch,
        );
        if !rows.is_empty() {
            rows[3 * len..].copy_from_slice(&scratch[..3 * len]);
        }
        Ok([g[0], g[1], g[2], a[0], a[1], a[2]])
    }

    /// The IMU update.
    pub(super) fn imu(
        &mut self,
        gyro: Option<[f64; 3]>,
        accel: Option<[f64; 3]>,
    ) -> Result<(), M::Error> {
        let t = self.estimate.t;
        let Some(imu) = self.noise.imu else {
            return Err(EstimateError::NoSensor { t, sensor: "imu" });
        };
        if let Some(g) = &gyro {
            check_finite(t, "gyro", g)?;
        }
        if let Some(a) = &accel {
            check_finite(t, "accel", a)?;
        }
        self.begin();
        if let Some(reading) = accel {
            self.linearize_here(Need::Current)?;
            let y = &self.estimate.y;
            let (_, t_inv) = error_map(&y[ATTITUDE]);
            let lin = &self.linearization;
            let h = measure::accelerometer(
                &self.layout,
                (y, &lin.f, &lin.jac),
                &self.estimate.bias,
                &imu,
                self.model.gravity(),
                &t_inv,
                &mut self.work.rows,
            );
            for axis in 0..3 {
                self.take_row(axis);
                let model = self.config.accel_model_sigma;
                self.scalar(
                    reading[axis] - h[axis],
                    imu.accel_variance + model * model,
                    "accelerometer",
                    axis,
                )?;
            }
        }
        if let Some(reading) = gyro {
            let h = measure::gyro(
                &self.layout,
                &self.estimate.y,
                &self.estimate.bias,
                &imu,
                &mut self.work.rows,
            );
            for axis in 0..3 {
                self.take_row(axis);
                self.scalar(reading[axis] - h[axis], imu.gyro_variance, "gyro", axis)?;
            }
        }
        self.inject()
    }

    /// Row `axis` of `work.rows` into `work.row`.
    fn take_row(&mut self, axis: usize) {
        let len = self.layout.len;
        self.work
            .row
            .copy_from_slice(&self.work.rows[axis * len..(axis + 1) * len]);
    }

    /// The wheel encoders' update: the mean rate since the last reading,
    /// `(θ_k − θ_k⁻)/Δt`, against the model's rate at the estimate, of
    /// variance `res²/(6·Δt²)` (each angle quantized to `res`, uniform
    /// error of variance `res²/12`, two readings per rate) plus
    /// `wheel_rate_sigma²`.
    pub(super) fn wheel_angles(&mut self, angles: &[f64]) -> Result<(), M::Error> {
        let t = self.estimate.t;
        let Some(resolution) = self.noise.encoder_resolution else {
            return Err(EstimateError::NoSensor {
                t,
                sensor: "wheel_encoders",
            });
        };
        check_len("wheel_angles", self.layout.wheels, angles.len())?;
        check_finite(t, "wheel_angles", angles)?;
        let Some(before) = self.estimate.wheel_angles_t else {
            self.remember_wheel_angles(angles);
            return Ok(());
        };
        let interval = t - before;
        if interval.is_nan() || interval <= 0.0 {
            return Err(EstimateError::EncoderInterval { t, interval });
        }
        let (dim, len) = (self.layout.dim, self.layout.len);
        let work = &mut self.work;
        self.model
            .wheel_rates(
                t,
                &self.estimate.y,
                &mut work.rates,
                &mut work.rate_gradient,
            )
            .map_err(|source| EstimateError::Model { t, source })?;
        let (_, t_inv) = error_map(&self.estimate.y[ATTITUDE]);
        let sigma = self.config.wheel_rate_sigma;
        let variance = resolution * resolution / (6.0 * interval * interval) + sigma * sigma;
        self.begin();
        for k in 0..self.layout.wheels {
            let work = &mut self.work;
            work.row[..dim].copy_from_slice(&work.rate_gradient[k * dim..(k + 1) * dim]);
            work.row[dim..len].iter_mut().for_each(|v| *v = 0.0);
            to_error_coordinates(&mut work.row, &t_inv);
            let rate = (angles[k] - self.estimate.wheel_angles[k]) / interval;
            let residual = rate - self.work.rates[k];
            self.scalar(residual, variance, "wheel encoder", k)?;
        }
        self.inject()?;
        self.remember_wheel_angles(angles);
        Ok(())
    }

    fn remember_wheel_angles(&mut self, angles: &[f64]) {
        self.estimate.wheel_angles.copy_from_slice(angles);
        self.estimate.wheel_angles_t = Some(self.estimate.t);
    }

    /// The suspension encoders' update: each coordinate read directly,
    /// its quantization's variance by the coordinate's rate
    /// (`SuspensionNoise::variance`), `√(ẏ² + σ_ẏ²)` at the estimate.
    pub(super) fn suspension(&mut self, values: &[f64]) -> Result<(), M::Error> {
        let t = self.estimate.t;
        let Some(noise) = self.noise.suspension else {
            return Err(EstimateError::NoSensor {
                t,
                sensor: "suspension_encoders",
            });
        };
        let n = self.layout.n;
        check_len("suspension", n - 6, values.len())?;
        check_finite(t, "suspension", values)?;
        self.begin();
        let len = self.layout.len;
        for (i, z) in values.iter().enumerate() {
            let residual = z - self.estimate.y[6 + i];
            // The coordinate's rate: its estimate with its uncertainty.
            let k = n + 6 + i;
            let (rate, variance) = (self.estimate.y[k], self.estimate.p[k * len + k]);
            let speed = libm::sqrt(rate * rate + variance);
            self.unit_row(6 + i);
            self.scalar(residual, noise.variance(speed), "suspension encoder", i)?;
        }
        self.inject()
    }

    /// A position fix of G.
    pub(super) fn position(&mut self, position: [f64; 3]) -> Result<(), M::Error> {
        let t = self.estimate.t;
        let Some(variance) = self.noise.position_variance else {
            return Err(EstimateError::NoSensor {
                t,
                sensor: "position_fix",
            });
        };
        check_finite(t, "position", &position)?;
        self.begin();
        for (i, z) in position.iter().enumerate() {
            let residual = z - self.estimate.y[i];
            self.unit_row(i);
            self.scalar(residual, variance, "position fix", i)?;
        }
        self.inject()
    }

    /// A heading fix: `h = ψ`, its row `[0, 0, 1]·T⁻¹` against δθ, the
    /// innovation wrapped into (−π, π].
    pub(super) fn heading(&mut self, heading: f64) -> Result<(), M::Error> {
        let t = self.estimate.t;
        let Some(variance) = self.noise.heading_variance else {
            return Err(EstimateError::NoSensor {
                t,
                sensor: "heading_fix",
            });
        };
        check_finite(t, "heading", &[heading])?;
        self.begin();
        let (_, t_inv) = error_map(&self.estimate.y[ATTITUDE]);
        self.unit_row(5);
        to_error_coordinates(&mut self.work.row, &t_inv);
        let residual = wrap(heading - self.estimate.y[5]);
        self.scalar(residual, variance, "heading fix", 0)?;
        self.inject()
    }

    /// `work.row = e_i`.
    fn unit_row(&mut self, i: usize) {
        self.work.row.iter_mut().for_each(|v| *v = 0.0);
        self.work.row[i] = 1.0;
    }

    /// Starts a sensor's updates: no correction yet.
    fn begin(&mut self) {
        self.work.correction.iter_mut().for_each(|v| *v = 0.0);
    }

    /// One scalar reading of row `work.row`, residual `z − h(ŷ)` at the
    /// linearization, variance `r` (module docs).
    fn scalar(
        &mut self,
        residual: f64,
        r: f64,
        what: &'static str,
        index: usize,
    ) -> Result<(), M::Error> {
        let t = self.estimate.t;
        let len = self.layout.len;
        let work = &mut self.work;
        let p = &mut self.estimate.p;
        let mut count = 0;
        for (i, h) in work.row.iter().enumerate() {
            if *h != 0.0 {
                work.nonzero[count] = i;
                count += 1;
            }
        }
        let nonzero = &work.nonzero[..count];
        // u = P·Hᵀ = Σ_k H_k·P[k, :] (P symmetric): whole rows.
        let u = &mut work.gain;
        super::dense::gather(u, p, len, &work.row, nonzero);
        let mut s = r;
        let mut predicted = 0.0;
        for &k in nonzero {
            s += work.row[k] * u[k];
            predicted += work.row[k] * work.correction[k];
        }
        if !(s > 0.0 && s.is_finite()) {
            return Err(EstimateError::NotPositiveDefinite {
                t,
                what: what_variance(what),
                index,
                value: s,
            });
        }
        let nu = residual - predicted;
        super::dense::axpy(&mut work.correction, nu / s, u);
        // P −= k·kᵀ with k = u/√s.
        let scale = 1.0 / libm::sqrt(s);
        u.iter_mut().for_each(|v| *v *= scale);
        super::dense::downdate(p, u, len);
        Ok(())
    }

    /// Applies the accumulated correction to the estimate, the
    /// covariance's diagonal checked first (once for a sensor's rows).
    fn inject(&mut self) -> Result<(), M::Error> {
        check_diagonal(
            &self.estimate.p,
            self.layout.len,
            self.estimate.t,
            "covariance diagonal after an update, component",
        )?;
        let correction = core::mem::take(&mut self.work.correction);
        let result = self.correct(&correction);
        self.work.correction = correction;
        result
    }

    /// Applies an error-state correction `delta` (`error_dim` long) to
    /// the estimate, as an update does: additive but for the attitude,
    /// turned by `R ← exp(δθ×)·R` and its Euler angles read back (ψ kept
    /// within π of its value), and the biases. The covariance is left as
    /// it is.
    pub fn correct(&mut self, delta: &[f64]) -> Result<(), M::Error> {
        let Self {
            layout, estimate, ..
        } = self;
        let t = estimate.t;
        check_len("correction", layout.len, delta.len())?;
        check_finite(t, "correction", delta)?;
        let y = &mut estimate.y;
        for i in (0..layout.dim).filter(|i| !ATTITUDE.contains(i)) {
            y[i] += delta[i];
        }
        let turned = mat_mul(
            &rotation::exp([delta[3], delta[4], delta[5]]),
            &rotation::rotation(&y[ATTITUDE]),
        );
        let angles = rotation::euler(&turned, y[5]);
        y[ATTITUDE].copy_from_slice(&angles);
        if layout.imu {
            for (b, d) in estimate.bias.iter_mut().zip(&delta[layout.dim..]) {
                *b += d;
            }
        }
        estimate.version += 1;
        check_finite(t, "corrected state", y)
    }

    /// The error-state deviation of the model state `truth` from the
    /// estimate into `out` (`dim` long, the biases left out): `truth − ŷ`
    /// but for the attitude, the small rotation δθ = log(R_true·R̂ᵀ).
    pub fn deviation(&self, truth: &[f64], out: &mut [f64]) -> Result<(), M::Error> {
        let dim = self.layout.dim;
        check_len("truth", dim, truth.len())?;
        check_len("deviation", dim, out.len())?;
        check_finite(self.estimate.t, "truth", truth)?;
        for (o, (a, b)) in out.iter_mut().zip(truth.iter().zip(&self.estimate.y)) {
            *o = a - b;
        }
        let turn = rotation::log(&mat_mul(
            &rotation::rotation(&truth[ATTITUDE]),
            &transpose(&rotation::rotation(&self.estimate.y[ATTITUDE])),
        ));
        out[ATTITUDE].copy_from_slice(&turn);
        Ok(())
    }
}

/// What a linearization at the estimate needs besides the right-hand
/// side.
#[derive(Clone, Copy)]
enum Need {
    /// No Jacobian.
    Rhs,
    /// A Jacobian that may still serve (`jacobian_every`).
    Current,
    /// The Jacobian at the estimate itself.
    Exact,
}

/// The name of a reading's innovation variance.
fn what_variance(what: &'static str) -> &'static str {
    match what {
        "accelerometer" => "accelerometer innovation variance, axis",
        "gyro" => "gyro innovation variance, axis",
        "wheel encoder" => "wheel encoder innovation variance, wheel",
        "suspension encoder" => "suspension encoder innovation variance, coordinate",
        "position fix" => "position fix innovation variance, axis",
        _ => "heading fix innovation variance",
    }
}

/// Every diagonal entry of `p` positive and finite.
pub(super) fn check_diagonal<E>(
    p: &[f64],
    len: usize,
    t: f64,
    what: &'static str,
) -> Result<(), E> {
    for i in 0..len {
        let v = p[i * len + i];
        if !(v > 0.0 && v.is_finite()) {
            return Err(EstimateError::NotPositiveDefinite {
                t,
                what,
                index: i,
                value: v,
            });
        }
    }
    Ok(())
}
