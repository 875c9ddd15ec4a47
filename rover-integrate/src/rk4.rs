//! Classical fixed-step Runge–Kutta method of order 4.

use super::call_check::check_call;
use super::step_size::fixed_steps;
use super::{ConfigError, FixedStepConfig, IntegrateError, Integrator, OdeSystem, Stats};

/// The classical Runge–Kutta method (Kutta 1901; Hairer, Nørsett & Wanner I, §II.1, Table 1.2,
/// p. 138): explicit, 4 stages, order 4, fixed step.
/// ```text
/// k1 = f(t, y)            k2 = f(t + h/2, y + h/2·k1)
/// k3 = f(t + h/2, y + h/2·k2)   k4 = f(t + h, y + h·k3)
/// y ← y + h/6·(k1 + 2·k2 + 2·k3 + k4)
/// ```
/// Stable for `h·λ` inside a region reaching −2.785 on the real axis and ±2.828 on the
/// imaginary one, so the step must resolve the fastest mode (the tyre's vertical stiffness on
/// a rover). Four right-hand-side evaluations per step and no allocation after [`Rk4::new`]:
/// the real-time path.
#[derive(Debug, Clone)]
pub struct Rk4 {
    dim: usize,
    step: f64,
    k1: Vec<f64>,
    k2: Vec<f64>,
    k3: Vec<f64>,
    k4: Vec<f64>,
    stage: Vec<f64>,
    stats: Stats,
}

impl Rk4 {
    /// RK4 for states of dimension `dim`, with its workspace allocated here.
    pub fn new(dim: usize, config: &FixedStepConfig) -> Result<Self, ConfigError> {
        config.validate("rk4")?;
        Ok(Self {
            dim,
            step: config.step,
            k1: vec![0.0; dim],
            k2: vec![0.0; dim],
            k3: vec![0.0; dim],
            k4: vec![0.0; dim],
            stage: vec![0.0; dim],
            stats: Stats::default(),
        })
    }

    /// The configured step \[s\].
    pub fn step(&self) -> f64 {
        self.step
    }

    /// One step of size `h` from `(t, y)`; `y` is overwritten with the result.
    fn step_once<S: OdeSystem + ?Sized>(
        &mut self,
        sys: &mut S,
        t: f64,
        h: f64,
        y: &mut [f64],
    ) -> Result<(), IntegrateError<S::Error>> {
        let half = 0.5 * h;
        eval(sys, t, y, &mut self.k1, &mut self.stats)?;
        axpy(&mut self.stage, y, half, &self.k1);
        eval(sys, t + half, &self.stage, &mut self.k2, &mut self.stats)?;
        axpy(&mut self.stage, y, half, &self.k2);
        eval(sys, t + half, &self.stage, &mut self.k3, &mut self.stats)?;
        axpy(&mut self.stage, y, h, &self.k3);
        eval(sys, t + h, &self.stage, &mut self.k4, &mut self.stats)?;
        let sixth = h / 6.0;
        let stages = self.k1.iter().zip(&self.k2).zip(&self.k3).zip(&self.k4);
        for (yi, (((k1, k2), k3), k4)) in y.iter_mut().zip(stages) {
            *yi += sixth * (k1 + 2.0 * (k2 + k3) + k4);
        }
        Ok(())
    }
}

/// `out = y + a·k`.
fn axpy(out: &mut [f64], y: &[f64], a: f64, k: &[f64]) {
    for ((o, yi), ki) in out.iter_mut().zip(y).zip(k) {
        *o = yi + a * ki;
    }
}

/// `dy = f(t, y)`, counted, the error tagged with `t`.
fn eval<S: OdeSystem + ?Sized>(
    sys: &mut S,
    t: f64,
    y: &[f64],
    dy: &mut [f64],
    stats: &mut Stats,
) -> Result<(), IntegrateError<S::Error>> {
    stats.rhs_evals += 1;
    sys.rhs(t, y, dy)
        .map_err(|source| IntegrateError::Rhs { t, source })
}

impl Integrator for Rk4 {
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
        let step = self.step;
        fixed_steps(step, t, y, t_target, |t, h, y| {
            self.step_once(sys, t, h, y)?;
            self.stats.steps += 1;
            sys.step_accepted(t + h, y);
            Ok(())
        })
    }

    fn restart(&mut self) {}

    fn stats(&self) -> Stats {
        self.stats
    }

    fn dim(&self) -> usize {
        self.dim
    }

    fn name(&self) -> &'static str {
        "rk4"
    }
}
