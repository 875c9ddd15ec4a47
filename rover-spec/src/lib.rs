//! Rover descriptions, validated into a [`rover_dynamics::Model`].
//!
//! A rover is described once — as TOML or as a [`Description`] built in
//! Rust — and [`load_file`], [`load_str`] or [`from_description`] turn it
//! into a [`Spec`]: the numeric model (body, suspension coordinates,
//! carried bodies with their polynomial kinematics, wheels) plus the names,
//! the fit reports and the rest geometry. Every problem is a located
//! [`Diagnostic`] (file:line:col, field path, the line with a caret, the
//! numbers, a `help:`), all of them in file order, in one [`SpecError`].
//!
//! # The TOML format
//!
//! SI units everywhere; an angle field `x` has a degree twin `x_deg` (give
//! one). The full reference is `docs/DESCRIPTION.md`; in short:
//!
//! ```toml
//! name = "swing2"
//! gravity = 1.62                       # m/s², along −Z
//!
//! [body]
//! mass = 30.0                          # kg
//! inertia = [0.7, 0.9, 1.5]            # kg·m², or [[..], [..], [..]]
//!
//! [wheel_defaults]                     # any wheel field, for every wheel
//! mass = 0.6
//! radius = 0.09
//! stiffness = 4000.0                   # k_w, N/m
//! damping = 300.0                      # c_w, N·s/m
//! mu_x = 0.5
//! mu_y = 0.5
//! cornering_stiffness = 50.0           # N/rad
//! max_torque = 1.29                    # N·m
//! motor = "body"                       # or "hub"
//!
//! [[suspension]]
//! name = "front"
//! kind = "longitudinal_swing_arm"      # see below for every kind
//! pivot = [0.18, 0.2, -0.01]
//! length = 0.2
//! coordinate = { rest_deg = -17.2, min_deg = -60, max_deg = -2, stiffness = 5.0, damping = 3.5 }
//! fit = { method = "taylor", terms = 5 }
//!
//! [[wheel]]
//! name = "front"
//! suspension = "front"                 # its point `wheel`
//! ```
//!
//! Suspension kinds (MODEL.md §3): `longitudinal_swing_arm`,
//! `transversal_swing_arm`, `double_wishbone`, `longitudinal_rocker`,
//! `transversal_rocker`, `rocker_bogie` and `polynomial` (Z_ij given
//! directly). Each library kind is converted to polynomials
//! `u_j = c_j + Σ_i Z_ij·[1, ξ_i, …, ξ_i^(k−1)]ᵀ`, ξ_i = y_i − y_ic, by a
//! Taylor series about the rest value or by least squares over the travel
//! (the `fit` table), and the fit's maximum error over the travel is
//! reported; an error above `fit.tolerance` is a located error.
//!
//! ```
//! let text = rover_models::builtin("swing4").unwrap();
//! let spec = rover_spec::load_str(text, "swing4").unwrap();
//! assert_eq!(spec.model.dof(), 10);
//! assert!((spec.model.total_mass() - 32.4).abs() < 1e-12);
//! ```
#![warn(missing_docs)]

mod checks;
pub mod description;
mod diagnostic;
mod document;
mod error;
pub mod fit;
pub mod jet;
pub mod linkage;
mod load;
pub mod point_fit;
pub mod real;
pub mod report;
pub mod sketch;
mod spec;
pub mod suspension;
mod validate;

/// The limits a description is checked against (docs/DESCRIPTION.md).
pub mod limits {
    pub use crate::validate::runnable::{MAX_DOF, MAX_GRAVITY, MAX_MAGNITUDE, MIN_BODY_MASS};
}

pub use description::Description;
pub use diagnostic::Diagnostic;
pub use error::SpecError;
pub use load::{MAX_NESTING, from_description, load_file, load_str, nesting_error, parse_str};
pub use rover_files::line_column;
pub use spec::{BodyFit, Spec, SuspensionInfo};
pub use validate::validate;
