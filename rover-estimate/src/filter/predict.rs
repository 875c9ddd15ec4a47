//! The prediction over `dt`, the commands held: the mean by linearly
//! implicit Euler steps (a Rosenbrock–Euler W-method) on the model's
//! Jacobian `J` at the step's start, the covariance by the same steps'
//! transition.
//!
//! ```text
//! A = I − h·J,  h = dt/m          (m = FilterConfig::substeps)
//! y ← y + h·A⁻¹·f(t, y)           (m times, J and A held)
//! Φ_y = A⁻ᵐ                       (∂y⁺/∂y of the steps, J held)
//! Φ = S(y⁺)·Φ_y·S(y)⁻¹  ⊕  e^(−dt/τ)·I₆   (error coordinates; biases)
//! P ← Φ·P·Φᵀ + diag(q²)·dt + dt²·σ_τ²·Σ_k b_k·b_kᵀ  ⊕  σ_b²·(1 − e^(−2dt/τ))
//! ```
//! `b_k = ∂f/∂τ_k` is the model's response to wheel `k`'s torque, by
//! differences every `torque_response_every` predictions
//! ([`super::FilterConfig::torque_sigma`]).
//! `S(y)` is the identity but for the attitude's block `T = R·E`
//! (`rotation::error_map`): `S(y⁺)·…·S(y)⁻¹` carries the frame's turn
//! over the step, so the attitude's error obeys `δθ̇ = R·δΩ` to first
//! order. The implicit step damps the tyres' stiff modes instead of
//! resolving them, as the runtime's ROS2 does (docs/PERFORMANCE.md); an
//! explicit step of 10 ms is unstable on them.

use rover_dynamics::linalg::M3;

use super::dense::{symmetrize, transpose_in_place};
use super::step_matrix::StepMatrix;
use super::update::check_diagonal;
use super::{ATTITUDE, EstimateError, Estimator, Layout, Result, check_finite, check_len};
use crate::process::ProcessModel;
use crate::rotation::error_map;

impl<M: ProcessModel> Estimator<M> {
    /// Advances the estimate by `dt` \[s\] under the motor torques [N·m]
    /// and steering angles \[rad\] the rover's computer commanded (one per
    /// wheel), held over the step.
    pub fn predict(&mut self, dt: f64, torques: &[f64], steering: &[f64]) -> Result<(), M::Error> {
        let t = self.estimate.t;
        if !(dt > 0.0 && dt.is_finite() && (t + dt) > t) {
            return Err(EstimateError::Step { t, dt });
        }
        let wheels = self.layout.wheels;
        check_len("torques", wheels, torques.len())?;
        check_len("steering", wheels, steering.len())?;
        check_finite(t, "torques", torques)?;
        check_finite(t, "steering", steering)?;
        self.guarded(|s| s.propagate(dt, torques, steering))
    }

    fn propagate(&mut self, dt: f64, torques: &[f64], steering: &[f64]) -> Result<(), M::Error> {
        let t = self.estimate.t;
        let model_error = |source| EstimateError::Model { t, source };
        self.model
            .set_inputs(torques, steering)
            .map_err(model_error)?;
        self.linearize_step()?;
        self.torque_response(torques, steering)?;
        for ((last, change), now) in self
            .estimate
            .torques
            .iter_mut()
            .zip(&mut self.estimate.torque_change)
            .zip(torques)
        {
            *change = if last.is_nan() { 0.0 } else { now - *last };
            *last = *now;
        }
        let substeps = self.config.substeps;
        let h = dt / substeps as f64;
        self.step
            .factor(&self.linearization.jac, h)
            .map_err(|_| EstimateError::SingularStep { t })?;
        let (_, start_inverse) = error_map(&self.estimate.y[ATTITUDE]);
        for s in 0..substeps {
            if s > 0 {
                let ts = t + s as f64 * h;
                self.model
                    .rhs(ts, &self.estimate.y, &mut self.work.step)
                    .map_err(|source| EstimateError::Model { t: ts, source })?;
            }
            self.step.solve_rows(&mut self.work.step, 1);
            for (y, k) in self.estimate.y.iter_mut().zip(&self.work.step) {
                *y += h * k;
            }
        }
        check_finite(t, "predicted state", &self.estimate.y)?;
        let (end, _) = error_map(&self.estimate.y[ATTITUDE]);
        self.propagate_covariance(dt, &start_inverse, &end)?;
        self.estimate.t += dt;
        self.estimate.version += 1;
        if let Some(age) = &mut self.linearization.jacobian_age {
            *age += 1;
        }
        Ok(())
    }

    /// The step's right-hand side at the estimate into `work.step`, and
    /// its Jacobian in `linearization.jac`: the last one while it may
    /// serve (taken by an update at this time's prior, before the
    /// correction, or within `jacobian_every` predictions: the W-method
    /// keeps its order with any approximate J), else both from one
    /// evaluation here.
    fn linearize_step(&mut self) -> Result<(), M::Error> {
        let t = self.estimate.t;
        let lin = &mut self.linearization;
        let model_error = |source| EstimateError::Model { t, source };
        if lin.jacobian_current(self.config.jacobian_every) {
            return self
                .model
                .rhs(t, &self.estimate.y, &mut self.work.step)
                .map_err(model_error);
        }
        self.model
            .rhs_and_jacobian(t, &self.estimate.y, &mut lin.f, &mut lin.jac)
            .map_err(model_error)?;
        lin.taken((t, self.estimate.version));
        self.work.step.copy_from_slice(&lin.f);
        Ok(())
    }

    /// `b_k = ∂f/∂τ_k` at the step's start into
    /// `linearization.torque_response` when it is due (module docs), from
    /// one right-hand side per wheel with its torque nudged;
    /// `work.step` holds `f` under `torques`.
    fn torque_response(&mut self, torques: &[f64], steering: &[f64]) -> Result<(), M::Error> {
        let lin = &mut self.linearization;
        if !self.config.torque_noise()
            || lin
                .torque_response_age
                .is_some_and(|age| age < self.config.torque_response_every)
        {
            return Ok(());
        }
        let t = self.estimate.t;
        let dim = self.layout.dim;
        let model_error = |source| EstimateError::Model { t, source };
        let work = &mut self.work;
        for k in 0..self.layout.wheels {
            work.nudged_torques.copy_from_slice(torques);
            let nudge = 1e-3 * (1.0 + libm::fabs(torques[k]));
            work.nudged_torques[k] += nudge;
            self.model
                .set_inputs(&work.nudged_torques, steering)
                .map_err(model_error)?;
            self.model
                .rhs(t, &self.estimate.y, &mut work.nudged_rhs)
                .map_err(model_error)?;
            let row = &mut lin.torque_response[k * dim..(k + 1) * dim];
            for ((b, nudged), f) in row.iter_mut().zip(&work.nudged_rhs).zip(&work.step) {
                *b = (nudged - f) / nudge;
            }
        }
        self.model
            .set_inputs(torques, steering)
            .map_err(model_error)?;
        lin.torque_response_age = Some(0);
        Ok(())
    }

    /// `P ← Φ·P·Φᵀ + Q` (module docs), `start_inverse = T(y)⁻¹` and
    /// `end = T(y⁺)`.
    fn propagate_covariance(
        &mut self,
        dt: f64,
        start_inverse: &M3<f64>,
        end: &M3<f64>,
    ) -> Result<(), M::Error> {
        let layout = self.layout;
        let len = layout.len;
        let bias = self.noise.imu.map(|imu| {
            let decay = libm::exp(-dt / imu.bias_time);
            let keep = 1.0 - decay * decay;
            (
                decay,
                imu.gyro_bias_sigma * imu.gyro_bias_sigma * keep,
                imu.accel_bias_sigma * imu.accel_bias_sigma * keep,
            )
        });
        let decay = bias.map_or(1.0, |b| b.0);
        let mut transition = Transition {
            layout: &layout,
            step: &mut self.step,
            substeps: self.config.substeps,
            start_inverse,
            end,
            decay,
        };
        let p = &mut self.estimate.p;
        transition.apply(p);
        for (i, q) in self.process_noise.iter().enumerate() {
            p[i * len + i] += q * dt;
        }
        if self.config.torque_noise() {
            let (sigma, follow) = (self.config.torque_sigma, self.config.torque_change_scale);
            let dim = layout.dim;
            let responses = self.linearization.torque_response.chunks_exact(dim);
            for (b, change) in responses.zip(&self.estimate.torque_change) {
                let moving = follow * change;
                let scale = (sigma * sigma + moving * moving) * dt * dt;
                // A torque moves accelerations only: the attitude's rows
                // (Euler rates) of `b` are zero, and so in error
                // coordinates too.
                for (i, bi) in b.iter().enumerate() {
                    if *bi == 0.0 {
                        continue;
                    }
                    let row = &mut p[i * len..i * len + dim];
                    for (pij, bj) in row.iter_mut().zip(b) {
                        *pij += scale * bi * bj;
                    }
                }
            }
            if let Some(age) = &mut self.linearization.torque_response_age {
                *age += 1;
            }
        }
        if let Some((decay, gyro, accel)) = bias {
            let (g, a) = (layout.gyro_bias(), layout.accel_bias());
            for i in 0..3 {
                p[(g + i) * len + g + i] += gyro;
                p[(a + i) * len + a + i] += accel;
            }
            self.estimate.bias.iter_mut().for_each(|b| *b *= decay);
        }
        check_diagonal(
            p,
            len,
            self.estimate.t,
            "covariance diagonal after a prediction, component",
        )
    }
}

/// The step's transition Φ in error coordinates (module docs).
struct Transition<'a> {
    layout: &'a Layout,
    step: &'a mut StepMatrix,
    substeps: usize,
    start_inverse: &'a M3<f64>,
    end: &'a M3<f64>,
    /// The biases' `e^(−dt/τ)`.
    decay: f64,
}

impl Transition<'_> {
    /// `P ← Φ·P·Φᵀ`: `Φ·(Φ·P)ᵀ`, `P` symmetric, in the copy compiled for
    /// x86-64-v4 when the processor has it (`dense`'s module docs).
    fn apply(&mut self, p: &mut [f64]) {
        #[cfg(target_arch = "x86_64")]
        if rover_dynamics::cpu::x86_64_v4() {
            // SAFETY: the processor has the features (checked just above).
            return unsafe { self.apply_v4(p) };
        }
        self.apply_portable(p)
    }

    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2,fma,avx512f,avx512vl")]
    unsafe fn apply_v4(&mut self, p: &mut [f64]) {
        self.apply_portable(p)
    }

    #[inline(always)]
    fn apply_portable(&mut self, p: &mut [f64]) {
        let len = self.layout.len;
        self.apply_rows(p);
        transpose_in_place(p, len);
        self.apply_rows(p);
        symmetrize(p, len);
    }

    /// `P ← Φ·P`, on whole rows: the attitude's rows to Euler
    /// increments, the model's rows through `A⁻ᵐ`, the attitude's back to
    /// δθ at the step's end, the biases' rows decayed.
    #[inline(always)]
    fn apply_rows(&mut self, p: &mut [f64]) {
        let len = self.layout.len;
        turn_rows(p, len, self.start_inverse);
        for _ in 0..self.substeps {
            self.step.solve_rows(p, len);
        }
        turn_rows(p, len, self.end);
        if self.layout.imu {
            p[self.layout.dim * len..]
                .iter_mut()
                .for_each(|v| *v *= self.decay);
        }
    }
}

/// The attitude's three rows of `p` (`len` columns) ← `m`·those rows.
#[inline(always)]
fn turn_rows(p: &mut [f64], len: usize, m: &M3<f64>) {
    let rows = &mut p[ATTITUDE.start * len..ATTITUDE.end * len];
    let (r0, rest) = rows.split_at_mut(len);
    let (r1, r2) = rest.split_at_mut(len);
    for j in 0..len {
        let v = [r0[j], r1[j], r2[j]];
        r0[j] = m[0][0] * v[0] + m[0][1] * v[1] + m[0][2] * v[2];
        r1[j] = m[1][0] * v[0] + m[1][1] * v[1] + m[1][2] * v[2];
        r2[j] = m[2][0] * v[0] + m[2][1] * v[1] + m[2][2] * v[2];
    }
}
