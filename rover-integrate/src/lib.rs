//! ODE integrators: advance the rover state `y = [x; w]`, `ẋ = B(x)·w`, `ẇ = a(x, w)`, from one
//! event time (an output instant, a controller sample) to the next, controls held constant in
//! between (zero-order hold).
//!
//! | method | kind | order | stability | per step | use it for |
//! |---|---|---|---|---|---|
//! | [`Rk4`] (`rk4`) | explicit RK, fixed step | 4 | h·λ within ≈ −2.8 (real axis) | 4 `f` | real-time path, smooth motion |
//! | [`SemiImplicitEuler`] (`semi_implicit_euler`) | symplectic, fixed step | 1 | h·ω < 2 (undamped) | 2 `f` (or `f` + `ẋ`) | real-time path, long runs with bounded energy error; teaching |
//! | [`Dopri5`] (`dopri5`) | explicit embedded RK 5(4), adaptive | 5 | ≈ −3.3 (real axis) | 6 `f` | accurate runs, reference solutions |
//! | [`Bdf`] (`bdf`) | implicit NDF/BDF multistep, variable order and step | 1–5 | A (k ≤ 2), A(α) | ≈ 1–4 `f`, rare `J` + LU | stiff tyre contact, as the paper's ode15s |
//! | [`Ros2`] (`ros2`) | linearly implicit Rosenbrock, fixed step | 2 | L | 2 `f` + `J` + LU | real-time path at steps of milliseconds, stiff contact |
//!
//! References: Rk4 — Hairer, Nørsett & Wanner, *Solving ODEs I* (2nd ed.), §II.1, p. 138.
//! Semi-implicit Euler — Hairer, Lubich & Wanner, *Geometric Numerical Integration*, §I.1.2,
//! Thm VI.3.3. Ros2 — Verwer, Spee, Blom & Hundsdorfer (1999), SIAM J. Sci. Comput. 20(4);
//! HW II, §IV.7. Dopri5 — Dormand & Prince (1980); HNW I, §II.4–5, pp. 167–178 (starting step
//! p. 169, PI control in Hairer & Wanner, *Solving ODEs II*, §IV.2). Bdf — Shampine & Reichelt
//! (1997), "The MATLAB ODE Suite", SIAM J. Sci. Comput. 18(1); HW II, §III.1, §IV.8.
//!
//! **Why our own adaptive methods.** The `differential-equations` crate has DOPRI5 and BDF,
//! but its `State` trait requires `Copy` (scalars, `SMatrix`, `[f64; N]`): the dimension
//! must be a compile-time constant, while a rover's `2n` is read from its description at run
//! time; its right-hand side cannot fail with an error of ours either. Dispatching over every possible `N` would multiply compile time for one feature.
//! The methods here work on slices of any length, propagate the system's error with the time
//! of the failing evaluation, keep their step size across calls, land exactly on each target,
//! and allocate their workspace once, in `new` (`tests/allocations.rs` counts 0 allocations
//! per step for RK4, semi-implicit Euler, Dopri5 and BDF).
//!
//! **Using them.** Build one from an [`IntegratorConfig`] (a scenario file's
//! `[integrator.<method>]` table) with [`IntegratorConfig::build`], then call
//! [`Integrator::advance`] for each interval. After changing the controls, call
//! [`Integrator::restart`] so the adaptive methods do not carry derivative (FSAL) or multistep
//! history across the jump; a state changed between calls is detected and restarts them too.
//! Errors ([`IntegrateError`]) name the time: a failing right-hand side, a step below
//! `min_step`, too many steps, a non-finite state component.
//!
//! ```
//! use rover_integrate::{Integrator, IntegratorConfig, OdeSystem};
//!
//! /// ẏ = −y.
//! struct Decay;
//! impl OdeSystem for Decay {
//!     type Error = std::convert::Infallible;
//!     fn dim(&self) -> usize { 1 }
//!     fn rhs(&mut self, _t: f64, y: &[f64], dy: &mut [f64]) -> Result<(), Self::Error> {
//!         dy[0] = -y[0];
//!         Ok(())
//!     }
//! }
//!
//! let config: IntegratorConfig = toml::from_str("[dopri5]\nrtol = 1e-8\natol = 1e-12").unwrap();
//! let mut integrator = config.build(1).unwrap();
//! let (mut t, mut y) = (0.0, [1.0]);
//! integrator.advance(&mut Decay, &mut t, &mut y, 1.0).unwrap();
//! assert_eq!(t, 1.0);
//! assert!((y[0] - (-1.0f64).exp()).abs() < 1e-7);
//! ```

#![warn(missing_docs)]

mod any_integrator;
mod bdf;
mod bdf_state;
mod call_check;
mod config;
mod config_error;
mod dopri5;
mod error;
mod integrator;
mod jacobian;
pub use jacobian::JacobianSource;
mod lu;
pub use lu::{Lu, Singular};
mod norm;
mod resume;
mod rk4;
mod ros2;
mod semi_implicit_euler;
mod stats;
mod step_size;
mod system;
mod tableau;

pub use any_integrator::AnyIntegrator;
pub use bdf::Bdf;
pub use config::{
    AdaptiveConfig, BDF_DEFAULT_RTOL, BdfConfig, FALLBACK_ERROR_SCALE, FixedStepConfig,
    IntegratorConfig,
};
pub use config_error::ConfigError;
pub use dopri5::Dopri5;
pub use error::IntegrateError;
pub use integrator::Integrator;
pub use rk4::Rk4;
pub use ros2::{Ros2, Ros2Config};
pub use semi_implicit_euler::SemiImplicitEuler;
pub use stats::Stats;
pub use system::OdeSystem;
