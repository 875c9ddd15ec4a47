//! Which integrator to use, with its parameters, as written in a scenario file.

use serde::{Deserialize, Serialize};

use super::{
    AnyIntegrator, Bdf, ConfigError, Dopri5, JacobianSource, Rk4, Ros2, Ros2Config,
    SemiImplicitEuler,
};

/// The integrator of a run: the method and its parameters. In TOML, one table named after
/// the method (unknown keys are rejected; omitted keys take the defaults below):
/// ```toml
/// [integrator.rk4]
/// step = 1e-3
///
/// # or
/// [integrator.dopri5]
/// rtol = 1e-6
/// atol = 1e-9
///
/// # or
/// [integrator.bdf]
/// rtol = 1e-4
/// max_order = 5
///
/// # or
/// [integrator.ros2]
/// step = 5e-3
/// ```
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case", deny_unknown_fields)]
pub enum IntegratorConfig {
    /// Classical fixed-step Runge–Kutta, order 4 (real-time path).
    Rk4(FixedStepConfig),
    /// Fixed-step semi-implicit (symplectic) Euler, order 1 (real-time path).
    SemiImplicitEuler(FixedStepConfig),
    /// Adaptive Dormand–Prince 5(4) (accurate non-stiff runs).
    Dopri5(AdaptiveConfig),
    /// Variable-order, variable-step NDF/BDF, orders 1–5 (stiff runs, like ode15s).
    Bdf(BdfConfig),
    /// Fixed-step linearly implicit Rosenbrock ROS2, order 2 (real-time path at long steps).
    Ros2(Ros2Config),
}

/// Parameters of a fixed-step method.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FixedStepConfig {
    /// Step size \[s\]. The last step before a target is shortened to land on it.
    pub step: f64,
}

/// Error control and limits of an adaptive explicit method.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct AdaptiveConfig {
    /// Relative tolerance of the local error (default 1e-6).
    pub rtol: f64,
    /// Absolute tolerance of the local error, in the state's SI units (default 1e-9).
    pub atol: f64,
    /// Largest step \[s\] (default: unbounded, `inf` in TOML).
    pub max_step: f64,
    /// Smallest step the controller may ask for before the run stops \[s\] (default 1e-10 s,
    /// far below the fastest rover time scale, a tyre's vertical mode at a few ms).
    pub min_step: f64,
    /// Step attempts allowed in one `advance` call (default 100 000).
    pub max_steps: u64,
}

impl Default for AdaptiveConfig {
    fn default() -> Self {
        Self {
            rtol: 1e-6,
            atol: 1e-9,
            max_step: f64::INFINITY,
            min_step: 1e-10,
            max_steps: 100_000,
        }
    }
}

/// Parameters of the variable-order stiff method.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct BdfConfig {
    /// Relative tolerance of the local error (default [`BDF_DEFAULT_RTOL`]).
    pub rtol: f64,
    /// Absolute tolerance of the local error, one value for every component, in the state's
    /// SI units, with the relative tolerance on every component. Default: none, and each
    /// component `i` gets `rtol·scale_i` from the system's
    /// [`error_scale`](crate::OdeSystem::error_scale) (a rover's: lengths, angles, velocities
    /// and rates each on their own scale), or `rtol·1e-5` where the system gives no scale.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub atol: Option<f64>,
    /// Highest order used, 1 to 5 (default 5, as ode15s). Orders 1–2 are A-stable; lower
    /// it to 2 for heavily damped oscillatory stiffness.
    pub max_order: usize,
    /// Numerical differentiation formulas (Klopfenstein–Shampine NDF, ode15s' default) when
    /// true (default), plain BDF when false.
    pub ndf: bool,
    /// Largest step \[s\] (default: unbounded).
    pub max_step: f64,
    /// Smallest step the controller may ask for before the run stops \[s\] (default 1e-10 s).
    pub min_step: f64,
    /// Step attempts allowed in one `advance` call (default 100 000).
    pub max_steps: u64,
    /// Where the Newton iterations' Jacobian comes from (default `"system"`: the rover's
    /// own where its plant has one, differences otherwise).
    pub jacobian: JacobianSource,
    /// The LU factors of the Newton matrix `I − c_lu·J` (`c = h/α`) serve a step of another
    /// `c` while `|c/c_lu − 1|` stays within this band, in [0, 1) (default 0.3, CVODE's): the
    /// Newton iteration then scales its corrections by `2/(1 + c/c_lu)` instead of factoring
    /// again. 0 factors again at every change of step size or order.
    pub lu_band: f64,
}

/// BDF's relative tolerance when a configuration gives none. With a rover's error scales
/// (`rover_runtime::sim::ErrorScale`) the absolute tolerances are 0.1 µm, 1 µrad, 10 µm/s and
/// 0.1 mrad/s.
pub const BDF_DEFAULT_RTOL: f64 = 1e-4;

/// The error scale of every component of a system that gives none
/// ([`OdeSystem::error_scale`](crate::OdeSystem::error_scale)), when no `atol` is given: with
/// the default `rtol`, an absolute tolerance of 1e-9.
pub const FALLBACK_ERROR_SCALE: f64 = 1e-5;

impl Default for BdfConfig {
    fn default() -> Self {
        Self {
            rtol: BDF_DEFAULT_RTOL,
            atol: None,
            max_order: 5,
            ndf: true,
            max_step: f64::INFINITY,
            min_step: 1e-10,
            max_steps: 100_000,
            jacobian: JacobianSource::System,
            lu_band: 0.3,
        }
    }
}

impl IntegratorConfig {
    /// The method's name as written in a scenario file.
    pub fn method(&self) -> &'static str {
        match self {
            Self::Rk4(_) => "rk4",
            Self::SemiImplicitEuler(_) => "semi_implicit_euler",
            Self::Dopri5(_) => "dopri5",
            Self::Bdf(_) => "bdf",
            Self::Ros2(_) => "ros2",
        }
    }

    /// Checks every parameter and reports the first one out of range.
    pub fn validate(&self) -> Result<(), ConfigError> {
        let method = self.method();
        match self {
            Self::Rk4(c) | Self::SemiImplicitEuler(c) => c.validate(method),
            Self::Dopri5(c) => c.validate(method),
            Self::Bdf(c) => c.validate(),
            Self::Ros2(c) => c.validate(),
        }
    }

    /// Validates and builds the integrator for states of dimension `dim`, its workspace
    /// allocated once here.
    pub fn build(&self, dim: usize) -> Result<AnyIntegrator, ConfigError> {
        Ok(match self {
            Self::Rk4(c) => AnyIntegrator::Rk4(Rk4::new(dim, c)?),
            Self::SemiImplicitEuler(c) => {
                AnyIntegrator::SemiImplicitEuler(SemiImplicitEuler::new(dim, c)?)
            }
            Self::Dopri5(c) => AnyIntegrator::Dopri5(Box::new(Dopri5::new(dim, c)?)),
            Self::Bdf(c) => AnyIntegrator::Bdf(Box::new(Bdf::new(dim, c)?)),
            Self::Ros2(c) => AnyIntegrator::Ros2(Box::new(Ros2::new(dim, c)?)),
        })
    }
}

impl FixedStepConfig {
    /// Checks `step`; `method` names the method in the message.
    pub fn validate(&self, method: &'static str) -> Result<(), ConfigError> {
        if !(self.step.is_finite() && self.step > 0.0) {
            return Err(bad(
                method,
                "step",
                self.step,
                "must be a positive, finite time step in seconds",
                "the real-time path typically uses 1e-4 to 1e-3 s",
            ));
        }
        Ok(())
    }
}

impl AdaptiveConfig {
    /// Checks every field; `method` names the method in the message.
    pub fn validate(&self, method: &'static str) -> Result<(), ConfigError> {
        check_tolerances(method, self.rtol, self.atol)?;
        check_limits(method, self.max_step, self.min_step, self.max_steps)
    }
}

impl BdfConfig {
    /// Checks every field.
    pub fn validate(&self) -> Result<(), ConfigError> {
        check_tolerances("bdf", self.rtol, self.atol.unwrap_or(1.0))?;
        if !(1..=5).contains(&self.max_order) {
            return Err(ConfigError {
                method: "bdf",
                field: "max_order",
                value: self.max_order.to_string(),
                problem: "must be 1, 2, 3, 4 or 5",
                hint: "5 is the default (as ode15s); 2 is the highest A-stable order",
            });
        }
        if !(0.0..1.0).contains(&self.lu_band) {
            return Err(bad(
                "bdf",
                "lu_band",
                self.lu_band,
                "must be in [0, 1)",
                "0.3 (the default) reuses the Newton matrix's LU factors while the step changes \
                 by less than 30 %; 0 factors again at every change",
            ));
        }
        check_limits("bdf", self.max_step, self.min_step, self.max_steps)
    }
}

/// Smallest relative tolerance accepted: below it roundoff dominates the error estimate
/// (Hairer, Nørsett & Wanner I, §II.4).
const RTOL_MIN: f64 = 1e-14;

fn check_tolerances(method: &'static str, rtol: f64, atol: f64) -> Result<(), ConfigError> {
    if !(RTOL_MIN..1.0).contains(&rtol) {
        return Err(bad(
            method,
            "rtol",
            rtol,
            "must be in [1e-14, 1)",
            "relative tolerances are typically 1e-3 (quick look) to 1e-8 (reference runs)",
        ));
    }
    if !(atol.is_finite() && atol > 0.0) {
        return Err(bad(
            method,
            "atol",
            atol,
            "must be a positive, finite number",
            "it is in the state's SI units (m, rad, m/s, rad/s); 1e-9 suits a rover",
        ));
    }
    Ok(())
}

fn check_limits(
    method: &'static str,
    max_step: f64,
    min_step: f64,
    max_steps: u64,
) -> Result<(), ConfigError> {
    if max_step.is_nan() || max_step <= 0.0 {
        return Err(bad(
            method,
            "max_step",
            max_step,
            "must be > 0 seconds (inf for no limit)",
            "leave it out for no limit, or use e.g. the controller's sample time",
        ));
    }
    if !(min_step.is_finite() && min_step >= 0.0 && min_step < max_step) {
        return Err(bad(
            method,
            "min_step",
            min_step,
            "must be a finite number of seconds, ≥ 0 and below `max_step`",
            "the default 1e-10 s stops a run whose steps collapse",
        ));
    }
    if max_steps == 0 {
        return Err(ConfigError {
            method,
            field: "max_steps",
            value: "0".to_owned(),
            problem: "must be at least 1",
            hint: "the default is 100000 step attempts per output interval",
        });
    }
    Ok(())
}

fn bad(
    method: &'static str,
    field: &'static str,
    value: f64,
    problem: &'static str,
    hint: &'static str,
) -> ConfigError {
    ConfigError {
        method,
        field,
        value: number(value),
        problem,
        hint,
    }
}

/// A number as a user would write it: plain in [1e-3, 1e6), in exponent form otherwise.
fn number(value: f64) -> String {
    let magnitude = value.abs();
    if value == 0.0 || !value.is_finite() || (1e-3..1e6).contains(&magnitude) {
        format!("{value}")
    } else {
        format!("{value:e}")
    }
}
