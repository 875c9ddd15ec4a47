//! A fixed-step, linearly implicit method for real-time loops: the two-stage Rosenbrock
//! method ROS2.

use serde::{Deserialize, Serialize};

use super::call_check::check_call;
use super::jacobian::{JacobianScratch, JacobianSource, jacobian};
use super::lu::Lu;
use super::step_size::fixed_steps;
use super::{ConfigError, IntegrateError, Integrator, OdeSystem, Stats};

/// `γ = 1 + 1/√2`: the value that makes ROS2 L-stable.
const GAMMA: f64 = 1.0 + core::f64::consts::FRAC_1_SQRT_2;

/// Parameters of [`Ros2`] (`[integrator.ros2]` in a scenario).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Ros2Config {
    /// Step size \[s\]. The last step before a target is shortened to land on it.
    pub step: f64,
    /// The Jacobian is evaluated every this many steps (default 1, every step). ROS2 keeps
    /// its order 2 with a Jacobian from earlier steps (it is a W-method), so a rig that needs
    /// a cheaper step can trade stability margin for cost; the cost per step is then uneven.
    #[serde(default = "one")]
    pub jacobian_every: u32,
    /// Where the Jacobian comes from (default `"system"`: the rover's own where its plant
    /// has one, differences otherwise).
    #[serde(default)]
    pub jacobian: JacobianSource,
}

fn one() -> u32 {
    1
}

impl Ros2Config {
    /// Checks every field.
    pub fn validate(&self) -> Result<(), ConfigError> {
        super::FixedStepConfig { step: self.step }.validate("ros2")?;
        if self.jacobian_every == 0 {
            return Err(ConfigError {
                method: "ros2",
                field: "jacobian_every",
                value: "0".to_owned(),
                problem: "must be at least 1",
                hint: "1 (the default) evaluates the Jacobian at every step",
            });
        }
        Ok(())
    }
}

/// The two-stage Rosenbrock method ROS2 (Verwer, Spee, Blom & Hundsdorfer, "A second-order
/// Rosenbrock method applied to photochemical dispersion problems", SIAM J. Sci. Comput. 20,
/// 1999; Hairer & Wanner II, §IV.7): linearly implicit, order 2, L-stable, fixed step.
/// ```text
/// W = I − γ·h·J,   J = ∂f/∂y (t_n, y_n),   f_t = ∂f/∂t (t_n, y_n),   γ = 1 + 1/√2
/// W·k1 = f(t_n, y_n) + γ·h·f_t
/// W·k2 = f(t_n + h, y_n + h·k1) − 2·k1 − γ·h·f_t
/// y_{n+1} = y_n + h·(3/2·k1 + 1/2·k2)
/// ```
/// The `f_t` terms (a forward difference in time, one more right-hand side) keep the order
/// where the forcing changes with time while stiff modes follow it: without them a stiff
/// component lags a time-varying command by O(1), not O(h²).
/// One LU factorization and three right-hand sides per step, plus the Jacobian: the system's
/// own when it has one, else forward differences (`dim` more right-hand sides). No Newton
/// iteration, so the cost of a step is the same at every step: what a real-time loop needs.
/// L-stability damps the stiff tyre and cornering modes at steps far beyond an explicit
/// method's limit instead of resolving them; the motion at the step's scale stays second
/// order. Order 2 holds for any `W` (a W-method), so an older Jacobian
/// ([`Ros2Config::jacobian_every`]) costs accuracy only through stability. The workspace,
/// including the dense Jacobian and its LU factors, is allocated in [`Ros2::new`]; steps
/// allocate nothing.
#[derive(Debug, Clone)]
pub struct Ros2 {
    dim: usize,
    config: Ros2Config,
    jac: Vec<f64>,
    scratch: JacobianScratch,
    lu: Lu,
    /// `γ·h` of the factors in `lu`; NaN when they are out of date.
    lu_gamma_h: f64,
    /// Steps since the Jacobian was evaluated; `None` before the first.
    jac_age: Option<u32>,
    f0: Vec<f64>,
    ft: Vec<f64>,
    k1: Vec<f64>,
    k2: Vec<f64>,
    stage: Vec<f64>,
    stats: Stats,
}

impl Ros2 {
    /// ROS2 for states of dimension `dim`, with its workspace allocated here.
    pub fn new(dim: usize, config: &Ros2Config) -> Result<Self, ConfigError> {
        config.validate()?;
        let v = || vec![0.0; dim];
        Ok(Self {
            dim,
            config: *config,
            jac: vec![0.0; dim * dim],
            scratch: JacobianScratch::new(dim, config.jacobian),
            lu: Lu::new(dim),
            lu_gamma_h: f64::NAN,
            jac_age: None,
            f0: v(),
            ft: v(),
            k1: v(),
            k2: v(),
            stage: v(),
            stats: Stats::default(),
        })
    }

    /// The configured step \[s\].
    pub fn step(&self) -> f64 {
        self.config.step
    }

    /// One step of size `h` from `(t, y)`; `y` is overwritten with the result.
    fn step_once<S: OdeSystem + ?Sized>(
        &mut self,
        sys: &mut S,
        t: f64,
        h: f64,
        y: &mut [f64],
    ) -> Result<(), IntegrateError<S::Error>> {
        self.stats.rhs_evals += 1;
        sys.rhs(t, y, &mut self.f0)
            .map_err(|source| IntegrateError::Rhs { t, source })?;
        if let Some(component) = self.f0.iter().position(|v| !v.is_finite()) {
            return Err(IntegrateError::NonFinite {
                t,
                component,
                value: self.f0[component],
            });
        }
        let fresh = match self.jac_age {
            Some(age) if age + 1 < self.config.jacobian_every => {
                self.jac_age = Some(age + 1);
                false
            }
            _ => {
                jacobian(
                    sys,
                    t,
                    y,
                    &self.f0,
                    &mut self.jac,
                    &mut self.scratch,
                    &mut self.stats,
                )?;
                self.jac_age = Some(0);
                true
            }
        };
        let gamma_h = GAMMA * h;
        if fresh || self.lu_gamma_h.to_bits() != gamma_h.to_bits() {
            self.stats.lu_decompositions += 1;
            if self.lu.factor_shifted(&self.jac, gamma_h).is_err() {
                self.lu_gamma_h = f64::NAN;
                // A singular W: the Jacobian has an eigenvalue at exactly 1/(γh), which no
                // physical state has; report it as the divergence it comes with.
                return Err(IntegrateError::NonFinite {
                    t,
                    component: 0,
                    value: f64::NAN,
                });
            }
            self.lu_gamma_h = gamma_h;
        }
        // f_t by a forward difference in time, scaled by γ·h.
        let dt = f64::EPSILON.sqrt() * t.abs().max(h.max(1.0));
        let t_dt = t + dt;
        self.stats.rhs_evals += 1;
        sys.rhs(t_dt, y, &mut self.ft)
            .map_err(|source| IntegrateError::Rhs { t: t_dt, source })?;
        let scale = gamma_h / (t_dt - t);
        for (ft, f0) in self.ft.iter_mut().zip(&self.f0) {
            *ft = scale * (*ft - f0);
        }
        for ((k1, f0), ft) in self.k1.iter_mut().zip(&self.f0).zip(&self.ft) {
            *k1 = f0 + ft;
        }
        self.lu.solve(&mut self.k1);
        for ((s, yi), k) in self.stage.iter_mut().zip(y.iter()).zip(&self.k1) {
            *s = yi + h * k;
        }
        self.stats.rhs_evals += 1;
        sys.rhs(t + h, &self.stage, &mut self.k2)
            .map_err(|source| IntegrateError::Rhs { t: t + h, source })?;
        for ((k2, k1), ft) in self.k2.iter_mut().zip(&self.k1).zip(&self.ft) {
            *k2 -= 2.0 * k1 + ft;
        }
        self.lu.solve(&mut self.k2);
        for ((yi, k1), k2) in y.iter_mut().zip(&self.k1).zip(&self.k2) {
            *yi += h * (1.5 * k1 + 0.5 * k2);
        }
        Ok(())
    }
}

impl Integrator for Ros2 {
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
        let step = self.config.step;
        fixed_steps(step, t, y, t_target, |t, h, y| {
            self.step_once(sys, t, h, y)?;
            self.stats.steps += 1;
            sys.step_accepted(t + h, y);
            Ok(())
        })
    }

    /// A jump in the right-hand side (new commands): the next step takes a fresh Jacobian.
    fn restart(&mut self) {
        self.jac_age = None;
    }

    fn stats(&self) -> Stats {
        self.stats
    }

    fn dim(&self) -> usize {
        self.dim
    }

    fn name(&self) -> &'static str {
        "ros2"
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `ẏ = λ·(y − cos t) − sin t`, exact solution `cos t` from y(0) = 1: stiff for λ ≪ 0
    /// (Prothero–Robinson).
    struct ProtheroRobinson(f64);

    impl OdeSystem for ProtheroRobinson {
        type Error = std::convert::Infallible;
        fn dim(&self) -> usize {
            1
        }
        fn rhs(&mut self, t: f64, y: &[f64], dy: &mut [f64]) -> Result<(), Self::Error> {
            dy[0] = self.0 * (y[0] - t.cos()) - t.sin();
            Ok(())
        }
    }

    fn error_at(lambda: f64, h: f64) -> f64 {
        let config = Ros2Config {
            step: h,
            jacobian_every: 1,
            jacobian: JacobianSource::Differences,
        };
        let mut m = Ros2::new(1, &config).unwrap();
        let (mut t, mut y) = (0.0, [1.0]);
        m.advance(&mut ProtheroRobinson(lambda), &mut t, &mut y, 1.0)
            .unwrap();
        (y[0] - 1.0f64.cos()).abs()
    }

    /// Second order on a non-stiff problem: halving the step divides the error by about 4.
    #[test]
    fn ros2_is_second_order() {
        let (coarse, fine) = (error_at(-1.0, 0.02), error_at(-1.0, 0.01));
        let rate = (coarse / fine).log2();
        assert!((rate - 2.0).abs() < 0.1, "observed order {rate}");
    }

    /// L-stable and still second order in the stiff limit: with λ = −1e8 (h·λ down to −1e7)
    /// the solution follows the smooth one, where an explicit method would blow up at any of
    /// these steps, and halving the step divides the error by about 4.
    #[test]
    fn ros2_damps_a_stiff_mode_at_long_steps() {
        let errors = [0.1, 0.05, 0.025].map(|h| error_at(-1e8, h));
        assert!(errors[0] < 3e-3, "{errors:?}");
        for pair in errors.windows(2) {
            let rate = (pair[0] / pair[1]).log2();
            assert!(rate > 1.8, "observed order {rate}: {errors:?}");
        }
    }
}
