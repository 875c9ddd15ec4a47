//! Variable-order, variable-step NDF/BDF for stiff problems (the ode15s family).

use super::bdf_state::BdfHistory;
use super::call_check::{check_call, first_non_finite};
use super::jacobian::{JacobianScratch, jacobian};
use super::lu::Lu;
use super::norm::{Atol, error_norm, scaled_norm};
use super::resume::Resume;
use super::step_size::{StartingStep, clamp_to_target, next_after_landing, starting_step};
use super::tableau::{BDF_GAMMA, BDF_MAX_ORDER, NDF_KAPPA};
use super::{
    BdfConfig, ConfigError, FALLBACK_ERROR_SCALE, IntegrateError, Integrator, OdeSystem, Stats,
};

/// Newton iterations allowed per step attempt.
const NEWTON_MAXITER: usize = 4;
/// Safety factor on predicted step sizes.
const SAFETY: f64 = 0.9;
/// Bounds on the step change after an error-test failure and after a success.
const MIN_FACTOR: f64 = 0.2;
const MAX_FACTOR: f64 = 10.0;
/// A step increase smaller than this is not taken (ode15s: 1.2).
const MIN_INCREASE: f64 = 1.2;

/// Step reduction after a Newton failure with a fresh Jacobian.
const NEWTON_FAILURE_FACTOR: f64 = 0.5;
/// Step reduction after a candidate state that is not finite.
const NON_FINITE_FACTOR: f64 = 0.25;
/// A step landing on a target that is shorter than this fraction of the wanted step is taken
/// from a copy of the history (see `advance`).
const SIDE_LANDING_RATIO: f64 = 0.999;

/// Variable-order (1–5), variable-step numerical differentiation formulas (NDF) or backward
/// differentiation formulas (BDF) in backward-difference form, after Shampine & Reichelt
/// (1997), "The MATLAB ODE Suite", SIAM J. Sci. Comput. 18 — the method of MATLAB's ode15s,
/// which the paper used — and Hairer & Wanner II, §III.1 and §IV.8. Implicit multistep;
/// orders 1–2 are A-stable, orders 3–5 A(α)-stable (BDF: α = 86°, 73°, 51°; the NDFs lose a
/// few degrees for a smaller error constant).
///
/// Each step: predict by extrapolating the backward differences, solve the corrector
/// ```text
/// (1 − κ_k)·γ_k·(y_{n+1} − y^(0)) + Σ_{m=1..k} γ_m·∇^m y_n − h·f(t_{n+1}, y_{n+1}) = 0
/// ```
/// by simplified Newton iterations with `I − c·J`, `c = h/((1 − κ_k)γ_k)`, factored again only
/// when `c` moves more than 30 % from the `c` of the factors in hand (a changed step size or
/// order within that band is corrected in the iteration, as CVODE does), the Jacobian `J`
/// (exact or finite differences) reused across steps and re-evaluated only when Newton fails
/// to converge with factors of the step's own `c` (then the step is halved if it fails again);
/// estimate the local error as `(κ_k·γ_k + 1/(k+1))·(y_{n+1} − y^(0))`; after `k + 1` steps at
/// one size, compare the errors the orders k − 1, k, k + 1 would make and take the order that
/// allows the largest step (Shampine & Reichelt, §2.3).
///
/// A step that has to be much shorter than wanted to land on a target is taken from a copy of
/// the history ("side landing"): the caller gets the solution at the target, while the history
/// stays on its regular grid and continues from there when the next call resumes from exactly
/// that solution. Committing the short step instead would let the next step-size change
/// amplify its Newton error by `(h/h_landing)^k` (frequent outputs then cost accuracy).
///
/// For stiff runs (a stiff tyre contact), where an explicit method's step is capped by
/// stability rather than accuracy. The workspace, including the dense Jacobian and its LU
/// factors (`dim²` each), is allocated in [`Bdf::new`]; steps allocate nothing.
#[derive(Debug, Clone)]
pub struct Bdf {
    config: BdfConfig,
    dim: usize,
    kappa: [f64; BDF_MAX_ORDER + 1],
    hist: BdfHistory,
    /// Time of the history's last point (behind the caller's time after a side landing).
    t_hist: f64,
    /// Room for a copy of the history, for side landings.
    spare: BdfHistory,
    jac: Vec<f64>,
    jac_scratch: JacobianScratch,
    /// A Jacobian has been computed (it survives restarts as a first approximation).
    have_jac: bool,
    /// The Jacobian was computed at the current step (no accepted step since).
    jac_current: bool,
    lu: Lu,
    /// `c = h/α` the factors in `lu` belong to; NaN when they are out of date.
    lu_c: f64,
    /// The last attempt's Newton iteration used factors of another `c` (within `lu_band`).
    lu_stale: bool,
    /// Each component's absolute tolerance (from `atol`, or `rtol` times the system's error
    /// scale), set at every start.
    atol: Vec<f64>,
    /// The weight of each component's relative tolerance (the system's, or 1).
    relative: Vec<f64>,
    y_pred: Vec<f64>,
    psi: Vec<f64>,
    d: Vec<f64>,
    delta: Vec<f64>,
    f: Vec<f64>,
    /// `f(t_{n+1}, y^(0))` from the first Newton iteration, for a Jacobian update there.
    f_pred: Vec<f64>,
    f_pred_valid: bool,
    y_new: Vec<f64>,
    /// Step the controller asks for next; 0 before the first step.
    h: f64,
    resume: Resume,
    stats: Stats,
}

/// Outcome of one attempted step.
enum Attempt {
    Accepted { err: f64 },
    ErrorTooLarge { err: f64 },
    NewtonFailed,
    NonFinite { component: usize, value: f64 },
}

impl Bdf {
    /// The NDF/BDF method for states of dimension `dim`, its workspace allocated here.
    pub fn new(dim: usize, config: &BdfConfig) -> Result<Self, ConfigError> {
        config.validate()?;
        let v = || vec![0.0; dim];
        Ok(Self {
            config: *config,
            dim,
            kappa: if config.ndf {
                NDF_KAPPA
            } else {
                [0.0; BDF_MAX_ORDER + 1]
            },
            hist: BdfHistory::new(dim),
            t_hist: 0.0,
            spare: BdfHistory::new(dim),
            jac: vec![0.0; dim * dim],
            jac_scratch: JacobianScratch::new(dim, config.jacobian),
            have_jac: false,
            jac_current: false,
            lu: Lu::new(dim),
            lu_c: f64::NAN,
            lu_stale: false,
            atol: v(),
            relative: vec![1.0; dim],
            y_pred: v(),
            psi: v(),
            d: v(),
            delta: v(),
            f: v(),
            f_pred: v(),
            f_pred_valid: false,
            y_new: v(),
            h: 0.0,
            resume: Resume::new(dim),
            stats: Stats::default(),
        })
    }

    /// The order the next step will use.
    pub fn order(&self) -> usize {
        self.hist.order
    }

    /// The step size the controller will try next \[s\] (0 before the first step).
    pub fn next_step(&self) -> f64 {
        self.h
    }

    /// Error constant of order `k`: `κ_k·γ_k + 1/(k+1)`.
    fn error_constant(&self, k: usize) -> f64 {
        self.kappa[k] * BDF_GAMMA[k] + 1.0 / (k as f64 + 1.0)
    }

    /// Each component's absolute tolerance and the weight of its relative one: the
    /// configuration's `atol` and 1 when it gives one, else `rtol` times the system's error
    /// scale and the system's weight (a scale that is not positive and finite, or none at
    /// all, counts as [`FALLBACK_ERROR_SCALE`]; a weight outside [0, 1] as 1).
    fn set_tolerances<S: OdeSystem + ?Sized>(&mut self, sys: &S) {
        let rtol = self.config.rtol;
        self.relative.fill(1.0);
        if let Some(atol) = self.config.atol {
            self.atol.fill(atol);
            return;
        }
        if !sys.error_scale(&mut self.atol, &mut self.relative) {
            self.atol.fill(FALLBACK_ERROR_SCALE);
            self.relative.fill(1.0);
        }
        for (a, r) in self.atol.iter_mut().zip(&mut self.relative) {
            let scale = if a.is_finite() && *a > 0.0 {
                *a
            } else {
                FALLBACK_ERROR_SCALE
            };
            *a = rtol * scale;
            *r = if (0.0..=1.0).contains(r) { *r } else { 1.0 };
        }
    }

    /// The absolute tolerance of each component in use (filled at the first step).
    pub fn absolute_tolerances(&self) -> &[f64] {
        &self.atol
    }

    /// Starts at order 1 from `(t, y)`: evaluates `f`, picks the starting step the first
    /// time, and evaluates the Jacobian if there is none yet.
    fn start<S: OdeSystem + ?Sized>(
        &mut self,
        sys: &mut S,
        t: f64,
        y: &[f64],
    ) -> Result<(), IntegrateError<S::Error>> {
        self.stats.rhs_evals += 1;
        sys.rhs(t, y, &mut self.f)
            .map_err(|source| IntegrateError::Rhs { t, source })?;
        self.set_tolerances(sys);
        if self.h <= 0.0 {
            let limits = StartingStep {
                rtol: self.config.rtol,
                atol: Atol::PerComponent {
                    atol: &self.atol,
                    relative: &self.relative,
                },
                order: 1,
                max_step: self.config.max_step,
            };
            self.h = starting_step(
                sys,
                t,
                y,
                &self.f,
                &limits,
                &mut self.y_new,
                &mut self.f_pred,
                &mut self.stats,
            )?;
        }
        self.hist.start(y, &self.f, self.h);
        self.lu_c = f64::NAN;
        self.jac_current = false;
        if !self.have_jac {
            jacobian(
                sys,
                t,
                y,
                &self.f,
                &mut self.jac,
                &mut self.jac_scratch,
                &mut self.stats,
            )?;
            self.have_jac = true;
            self.jac_current = true;
        }
        Ok(())
    }

    /// Re-evaluates the Jacobian at the predictor `(t_new, y^(0))` of the attempt that just
    /// failed, which `y_pred` still holds, with `f_pred = f(t_new, y^(0))` from that attempt's
    /// first Newton iteration when it got that far.
    ///
    /// The predictor is not recomputed from the history: after a side landing the history has
    /// been swapped back to the regular grid, whose predictor lies at another time and state.
    /// A forward difference `(f(y + δ·e_j) − f_pred)/δ` taken about a point that is not the one
    /// `f_pred` belongs to divides an `O(h·f)` mismatch by `δ ≈ 1e-8`: a Jacobian of garbage
    /// whose `(I − cJ)⁻¹` shrinks every Newton correction, so that unconverged iterates pass the
    /// convergence test and the error estimate (`tests/breakpoints.rs`: a torque step on an
    /// output instant, where such a refresh follows the restart).
    fn update_jacobian<S: OdeSystem + ?Sized>(
        &mut self,
        sys: &mut S,
        t_new: f64,
    ) -> Result<(), IntegrateError<S::Error>> {
        if !self.f_pred_valid {
            self.stats.rhs_evals += 1;
            sys.rhs(t_new, &self.y_pred, &mut self.f_pred)
                .map_err(|source| IntegrateError::Rhs { t: t_new, source })?;
        }
        jacobian(
            sys,
            t_new,
            &self.y_pred,
            &self.f_pred,
            &mut self.jac,
            &mut self.jac_scratch,
            &mut self.stats,
        )?;
        self.jac_current = true;
        self.lu_c = f64::NAN;
        Ok(())
    }

    /// One step from the history's last point to `t_new` (the history's step `h` apart).
    fn attempt<S: OdeSystem + ?Sized>(
        &mut self,
        sys: &mut S,
        t_new: f64,
    ) -> Result<Attempt, IntegrateError<S::Error>> {
        let rtol = self.config.rtol;
        let atol = Atol::PerComponent {
            atol: &self.atol,
            relative: &self.relative,
        };
        let k = self.hist.order;
        let alpha = (1.0 - self.kappa[k]) * BDF_GAMMA[k];
        let c = self.hist.h / alpha;
        self.hist.predict(&mut self.y_pred);
        self.hist.psi(alpha, &mut self.psi);
        self.f_pred_valid = false;

        // Factor again only when `c` left the band around the factors' own (or they are out
        // of date: NaN fails the test); within it, correct the step size in the iteration.
        let in_band = (c / self.lu_c - 1.0).abs() <= self.config.lu_band;
        if !in_band {
            self.stats.lu_decompositions += 1;
            if self.lu.factor_shifted(&self.jac, c).is_err() {
                self.lu_c = f64::NAN;
                self.lu_stale = false;
                return Ok(Attempt::NewtonFailed);
            }
            self.lu_c = c;
        }
        self.lu_stale = self.lu_c.to_bits() != c.to_bits();
        // (I − c_lu·J)⁻¹ for (I − c·J)⁻¹: the corrections of the linear part scaled by
        // 2/(1 + c/c_lu) (CVODE's step-size correction for a BDF with an older matrix).
        let correction = 2.0 / (1.0 + c / self.lu_c);

        // Simplified Newton on d = y_{n+1} − y^(0): (I − cJ)·Δ = c·f(y^(0) + d) − ψ − d,
        // stopped by the convergence-rate test of Hairer & Wanner II, §IV.8 (eq. 8.10–8.11).
        let newton_tol = (10.0 * f64::EPSILON / rtol).max(0.03_f64.min(rtol.sqrt()));
        self.d.fill(0.0);
        self.y_new.copy_from_slice(&self.y_pred);
        let mut norm_prev = f64::NAN;
        let mut converged = false;
        for iter in 0..NEWTON_MAXITER {
            self.stats.rhs_evals += 1;
            sys.rhs(t_new, &self.y_new, &mut self.f)
                .map_err(|source| IntegrateError::Rhs { t: t_new, source })?;
            if let Some(component) = first_non_finite(&self.f) {
                // Too far for the right-hand side: a shorter step, not a Jacobian from it.
                return Ok(Attempt::NonFinite {
                    component,
                    value: self.f[component],
                });
            }
            if iter == 0 {
                self.f_pred.copy_from_slice(&self.f);
                self.f_pred_valid = true;
            }
            for i in 0..self.dim {
                self.delta[i] = c * self.f[i] - self.psi[i] - self.d[i];
            }
            self.lu.solve(&mut self.delta);
            if self.lu_stale {
                for di in &mut self.delta {
                    *di *= correction;
                }
            }
            let norm = scaled_norm(&self.delta, &self.y_pred, rtol, atol);
            if !norm.is_finite() {
                break;
            }
            let rate = norm / norm_prev; // NaN on the first iteration
            // A correction already below the tolerance is the right-hand
            // side's own rounding (the contact search's crossings, say),
            // which does not shrink from one iteration to the next: accept
            // it rather than read its rate ≈ 1 as divergence. Otherwise a
            // rover at rest, whose predictor is already exact, fails every
            // step size down to `min_step` (as SUNDIALS does, after Hairer
            // & Wanner's rate test).
            let noise_floor = iter > 0 && norm < newton_tol;
            if !noise_floor
                && (rate >= 1.0
                    || rate.powi((NEWTON_MAXITER - iter) as i32) / (1.0 - rate) * norm > newton_tol)
            {
                break;
            }
            for i in 0..self.dim {
                self.y_new[i] += self.delta[i];
                self.d[i] += self.delta[i];
            }
            if norm == 0.0 || noise_floor || rate / (1.0 - rate) * norm < newton_tol {
                converged = true;
                break;
            }
            norm_prev = norm;
        }
        if !converged {
            return Ok(Attempt::NewtonFailed);
        }
        if let Some(component) = first_non_finite(&self.y_new) {
            return Ok(Attempt::NonFinite {
                component,
                value: self.y_new[component],
            });
        }
        // Local error estimate; `delta` is free again and holds it.
        let constant = self.error_constant(k);
        for (e, di) in self.delta.iter_mut().zip(&self.d) {
            *e = constant * di;
        }
        let err = error_norm(&self.delta, self.hist.row(0), &self.y_new, rtol, atol);
        Ok(if err <= 1.0 {
            Attempt::Accepted { err }
        } else {
            Attempt::ErrorTooLarge { err }
        })
    }

    /// After an accepted step of error `err` (history already committed): the order and the
    /// step-size factor for the next step (Shampine & Reichelt 1997, §2.3).
    fn select_order(&self, err: f64) -> (usize, f64) {
        let k = self.hist.order;
        if self.hist.equal_steps < k + 1 {
            return (k, 1.0);
        }
        let BdfConfig {
            rtol, max_order, ..
        } = self.config;
        let atol = Atol::PerComponent {
            atol: &self.atol,
            relative: &self.relative,
        };
        let y = self.hist.row(0);
        let factor_for = |order: usize, e: f64| e.powf(-1.0 / (order as f64 + 1.0));
        let mut best = (k, factor_for(k, err));
        if k > 1 {
            let e = self.error_constant(k - 1) * scaled_norm(self.hist.row(k), y, rtol, atol);
            let f = factor_for(k - 1, e);
            if f > best.1 {
                best = (k - 1, f);
            }
        }
        if k < max_order {
            let e = self.error_constant(k + 1) * scaled_norm(self.hist.row(k + 2), y, rtol, atol);
            let f = factor_for(k + 1, e);
            if f > best.1 {
                best = (k + 1, f);
            }
        }
        let (order, raw) = best;
        let factor = (SAFETY * raw).min(MAX_FACTOR);
        if order == k && factor < MIN_INCREASE {
            (k, 1.0)
        } else {
            (order, factor)
        }
    }
}

impl Bdf {
    /// [`Integrator::advance`] (`t_limit == t_target`) and
    /// [`Integrator::advance_output`]: steps may pass `t_target`, not `t_limit`, and the
    /// solution at `t_target` then comes from the interpolant of the step that passed it.
    fn advance_to<S: OdeSystem + ?Sized>(
        &mut self,
        sys: &mut S,
        t: &mut f64,
        y: &mut [f64],
        t_target: f64,
        t_limit: f64,
    ) -> Result<(), IntegrateError<S::Error>> {
        if check_call(self.dim, sys, *t, y, t_target)? {
            return Ok(());
        }
        if !self.resume.matches(*t, y) {
            self.start(sys, *t, y)?;
            self.t_hist = *t;
        }
        self.resume.invalidate();
        // An earlier call's last step may have passed this target already.
        if self.t_hist >= t_target {
            self.hist
                .interpolate((t_target - self.t_hist) / self.hist.h, y);
            *t = t_target;
            self.resume.record(*t, y);
            return Ok(());
        }
        let passing = t_limit > t_target;
        // A step passes the output instant by at most the span of this call, so that a run's
        // steps stay within about two output steps, as they do when every output lands.
        let reach = t_target + (t_target - *t);
        let BdfConfig {
            max_step,
            min_step,
            max_steps,
            ..
        } = self.config;
        let mut attempts = 0u64;
        // The history may lag the caller's time after a side landing (see below); the loop
        // runs on the history's time and reports accepted points past the caller's time.
        while *t < t_target {
            if attempts >= max_steps {
                return Err(IntegrateError::TooManySteps {
                    t: *t,
                    t_target,
                    max_steps,
                });
            }
            attempts += 1;
            let h_wanted = self.h.min(max_step);
            if h_wanted < min_step {
                return Err(IntegrateError::StepTooSmall {
                    t: self.t_hist,
                    h: h_wanted,
                    min_step,
                });
            }
            // Past the output instant while the step ends before the limit; else land on it.
            let h_pass = h_wanted.min(reach - self.t_hist);
            let (h, lands) = if passing && h_pass > 0.0 && self.t_hist + h_pass < t_limit {
                (h_pass, false)
            } else {
                clamp_to_target(self.t_hist, h_wanted, t_target)
            };
            // A landing step much shorter than the step the history is scaled for would, once
            // committed, have its Newton and rounding errors amplified by (h_wanted/h)^k when
            // the next step re-scales the differences back up. Such a step is taken from a
            // copy of the history instead ("side landing"): the caller gets the solution at
            // the target, the history stays at the last regular point and continues from
            // there when the next call resumes from exactly that solution.
            let side = lands && h < SIDE_LANDING_RATIO * h_wanted;
            if side {
                self.spare.copy_from(&self.hist);
                std::mem::swap(&mut self.hist, &mut self.spare);
            }
            if h != self.hist.h {
                self.hist.change_step(h / self.hist.h);
            }
            let t_new = if lands { t_target } else { self.t_hist + h };
            let attempt = self.attempt(sys, t_new);
            let accepted = matches!(attempt, Ok(Attempt::Accepted { .. }));
            if accepted {
                self.stats.steps += 1;
                self.jac_current = false;
                self.hist.commit(&self.d);
                if t_new > t_target {
                    // Passed the output instant: the interpolant of the step gives it.
                    self.hist.interpolate((t_target - t_new) / h, y);
                    *t = t_target;
                } else if t_new > *t {
                    *t = t_new;
                    y.copy_from_slice(self.hist.row(0));
                }
                // A side landing is a solution point but not the
                // history's: the next regular step starts before it.
                if !side {
                    sys.step_accepted(t_new, self.hist.row(0));
                }
            }
            if side {
                std::mem::swap(&mut self.hist, &mut self.spare);
                if accepted {
                    break;
                }
            }
            match attempt? {
                Attempt::Accepted { err } => {
                    self.t_hist = t_new;
                    let (order, factor) = self.select_order(err);
                    self.hist.order = order;
                    self.h = next_after_landing(h, h_wanted, factor);
                }
                Attempt::ErrorTooLarge { err } => {
                    self.stats.rejected_steps += 1;
                    let exponent = -1.0 / (self.hist.order as f64 + 1.0);
                    self.h = h * (SAFETY * err.powf(exponent)).clamp(MIN_FACTOR, 1.0);
                }
                Attempt::NewtonFailed => {
                    self.stats.rejected_steps += 1;
                    if self.lu_stale {
                        // Retry the same step with factors of its own `c` first.
                        self.lu_c = f64::NAN;
                    } else if self.jac_current {
                        self.h = h * NEWTON_FAILURE_FACTOR;
                    } else {
                        // Retry the same step with a fresh Jacobian.
                        self.update_jacobian(sys, t_new)?;
                    }
                }
                Attempt::NonFinite { component, value } => {
                    self.stats.rejected_steps += 1;
                    self.h = h * NON_FINITE_FACTOR;
                    if self.h < min_step {
                        return Err(IntegrateError::NonFinite {
                            t: t_new,
                            component,
                            value,
                        });
                    }
                }
            }
        }
        self.resume.record(*t, y);
        Ok(())
    }
}

impl Integrator for Bdf {
    fn advance<S: OdeSystem + ?Sized>(
        &mut self,
        sys: &mut S,
        t: &mut f64,
        y: &mut [f64],
        t_target: f64,
    ) -> Result<(), IntegrateError<S::Error>> {
        self.advance_to(sys, t, y, t_target, t_target)
    }

    fn advance_output<S: OdeSystem + ?Sized>(
        &mut self,
        sys: &mut S,
        t: &mut f64,
        y: &mut [f64],
        t_target: f64,
        t_limit: f64,
    ) -> Result<(), IntegrateError<S::Error>> {
        self.advance_to(sys, t, y, t_target, t_limit.max(t_target))
    }

    fn restart(&mut self) {
        self.resume.invalidate();
    }

    fn stats(&self) -> Stats {
        self.stats
    }

    fn dim(&self) -> usize {
        self.dim
    }

    fn name(&self) -> &'static str {
        "bdf"
    }
}
