//! Adaptive explicit Runge–Kutta: Dormand–Prince 5(4) with a PI step-size controller.

use super::call_check::{check_call, first_non_finite};
use super::norm::{Atol, error_norm};
use super::resume::Resume;
use super::step_size::{StartingStep, clamp_to_target, next_after_landing, starting_step};
use super::tableau::DOPRI5;
use super::{AdaptiveConfig, ConfigError, IntegrateError, Integrator, OdeSystem, Stats};

/// Safety factor on the predicted optimal step (Hairer, Nørsett & Wanner I, eq. II.4.13).
const SAFETY: f64 = 0.9;
/// Bounds on the step change from one step to the next (DOPRI5: 0.2 ≤ h_new/h ≤ 10).
const MIN_FACTOR: f64 = 0.2;
const MAX_FACTOR: f64 = 10.0;
/// PI controller exponents (Gustafsson 1991; Hairer & Wanner II, §IV.2, eq. 2.43c; the
/// values of Hairer's DOPRI5 code): `h_new = h·SAFETY·err^(−ALPHA)·err_prev^BETA`,
/// `ALPHA = 1/5 − 0.75·BETA`.
const BETA: f64 = 0.04;
const ALPHA: f64 = 0.2 - 0.75 * BETA;
/// Step reduction after a candidate state that is not finite.
const NON_FINITE_FACTOR: f64 = 0.25;

/// Dormand–Prince 5(4) (Dormand & Prince 1980; Hairer, Nørsett & Wanner I, §II.4–II.5,
/// pp. 167–178): explicit embedded Runge–Kutta pair, order 5 propagated, order 4 for the
/// error estimate, FSAL (6 evaluations per accepted step). Local error control in the
/// weighted RMS norm `‖e_i / (atol + rtol·max(|y_i|, |y_new,i|))‖ ≤ 1`, step size from a PI
/// controller (Gustafsson; Hairer & Wanner II, §IV.2). Not for stiff problems: its stability
/// region (reaching about −3.3 on the real axis) caps the step at the fastest mode whatever the
/// tolerance. For accurate runs and as the reference other methods are checked against.
///
/// The workspace is allocated in [`Dopri5::new`]; steps allocate nothing.
#[derive(Debug, Clone)]
pub struct Dopri5 {
    config: AdaptiveConfig,
    dim: usize,
    /// Stage derivatives `k_1..k_7`; `k[0]` holds `f(t, y)` between steps (FSAL).
    k: [Vec<f64>; 7],
    stage: Vec<f64>,
    y_new: Vec<f64>,
    err: Vec<f64>,
    /// Step the controller asks for next; 0 before the first step.
    h: f64,
    /// Error norm of the previous accepted step (for the PI controller).
    err_prev: f64,
    resume: Resume,
    stats: Stats,
}

/// Outcome of one attempted step.
enum Attempt {
    Accepted { err: f64 },
    Rejected { err: f64 },
    NonFinite { component: usize, value: f64 },
}

impl Dopri5 {
    /// Dormand–Prince 5(4) for states of dimension `dim`, its workspace allocated here.
    pub fn new(dim: usize, config: &AdaptiveConfig) -> Result<Self, ConfigError> {
        config.validate("dopri5")?;
        Ok(Self {
            config: *config,
            dim,
            k: std::array::from_fn(|_| vec![0.0; dim]),
            stage: vec![0.0; dim],
            y_new: vec![0.0; dim],
            err: vec![0.0; dim],
            h: 0.0,
            err_prev: 1e-4,
            resume: Resume::new(dim),
            stats: Stats::default(),
        })
    }

    /// The step size the controller will try next \[s\] (0 before the first step).
    pub fn next_step(&self) -> f64 {
        self.h
    }

    /// Evaluates `f(t, y)` into `k[0]` and, the first time, picks the starting step.
    fn start<S: OdeSystem + ?Sized>(
        &mut self,
        sys: &mut S,
        t: f64,
        y: &[f64],
    ) -> Result<(), IntegrateError<S::Error>> {
        self.stats.rhs_evals += 1;
        sys.rhs(t, y, &mut self.k[0])
            .map_err(|source| IntegrateError::Rhs { t, source })?;
        self.err_prev = 1e-4;
        if self.h <= 0.0 {
            let limits = StartingStep {
                rtol: self.config.rtol,
                atol: Atol::Uniform(self.config.atol),
                order: 4,
                max_step: self.config.max_step,
            };
            let (k0, rest) = self.k.split_at_mut(1);
            self.h = starting_step(
                sys,
                t,
                y,
                &k0[0],
                &limits,
                &mut self.stage,
                &mut rest[0],
                &mut self.stats,
            )?;
        }
        Ok(())
    }

    /// Stages 2..7 of a step of size `h` from `(t, y)` with `k[0] = f(t, y)`: fills `k`,
    /// `y_new` and the error estimate `err`, and judges the step.
    fn attempt<S: OdeSystem + ?Sized>(
        &mut self,
        sys: &mut S,
        t: f64,
        t_new: f64,
        h: f64,
        y: &[f64],
    ) -> Result<Attempt, IntegrateError<S::Error>> {
        for s in 1..7 {
            let (done, todo) = self.k.split_at_mut(s);
            let row = &DOPRI5.a[s][..s];
            for i in 0..self.dim {
                let mut sum = 0.0;
                for (aij, kj) in row.iter().zip(done.iter()) {
                    sum += aij * kj[i];
                }
                self.stage[i] = y[i] + h * sum;
            }
            let ts = if s == 6 { t_new } else { t + DOPRI5.c[s] * h };
            self.stats.rhs_evals += 1;
            sys.rhs(ts, &self.stage, &mut todo[0])
                .map_err(|source| IntegrateError::Rhs { t: ts, source })?;
        }
        // The seventh stage point is the propagated solution (FSAL).
        self.y_new.copy_from_slice(&self.stage);
        for i in 0..self.dim {
            let mut sum = 0.0;
            for (ej, kj) in DOPRI5.e.iter().zip(self.k.iter()) {
                sum += ej * kj[i];
            }
            self.err[i] = h * sum;
        }
        if let Some(component) = first_non_finite(&self.y_new) {
            return Ok(Attempt::NonFinite {
                component,
                value: self.y_new[component],
            });
        }
        let err = error_norm(
            &self.err,
            y,
            &self.y_new,
            self.config.rtol,
            Atol::Uniform(self.config.atol),
        );
        if !err.is_finite() {
            // A finite state with a non-finite error estimate: a stage blew up.
            return Ok(Attempt::NonFinite {
                component: first_non_finite(&self.err).unwrap_or(0),
                value: f64::NAN,
            });
        }
        Ok(if err <= 1.0 {
            Attempt::Accepted { err }
        } else {
            Attempt::Rejected { err }
        })
    }
}

impl Integrator for Dopri5 {
    fn advance<S: OdeSystem + ?Sized>(
        &mut self,
        sys: &mut S,
        t: &mut f64,
        y: &mut [f64],
        t_target: f64,
    ) -> Result<(), IntegrateError<S::Error>> {
        if check_call(self.dim, sys, *t, y, t_target)? {
            return Ok(());
        }
        if !self.resume.matches(*t, y) {
            self.start(sys, *t, y)?;
        }
        self.resume.invalidate();
        let AdaptiveConfig {
            max_step,
            min_step,
            max_steps,
            ..
        } = self.config;
        let mut attempts = 0u64;
        let mut after_rejection = false;
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
                    t: *t,
                    h: h_wanted,
                    min_step,
                });
            }
            let (h, lands) = clamp_to_target(*t, h_wanted, t_target);
            let t_new = if lands { t_target } else { *t + h };
            match self.attempt(sys, *t, t_new, h, y)? {
                Attempt::Accepted { err } => {
                    y.copy_from_slice(&self.y_new);
                    self.k.swap(0, 6);
                    *t = t_new;
                    self.stats.steps += 1;
                    sys.step_accepted(t_new, y);
                    let mut factor = (SAFETY * err.powf(-ALPHA) * self.err_prev.powf(BETA))
                        .clamp(MIN_FACTOR, MAX_FACTOR);
                    if after_rejection {
                        factor = factor.min(1.0);
                    }
                    self.h = next_after_landing(h, h_wanted, factor);
                    self.err_prev = err.max(1e-4);
                    after_rejection = false;
                }
                Attempt::Rejected { err } => {
                    self.stats.rejected_steps += 1;
                    let factor = (SAFETY * err.powf(-ALPHA)).clamp(MIN_FACTOR, 1.0);
                    self.h = h * factor;
                    after_rejection = true;
                }
                Attempt::NonFinite { component, value } => {
                    self.stats.rejected_steps += 1;
                    self.h = h * NON_FINITE_FACTOR;
                    after_rejection = true;
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
        "dopri5"
    }
}
