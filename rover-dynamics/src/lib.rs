//! The equations of motion of a wheeled rover in pseudo-coordinates
//! (F. Chen and G. Genta, Acta Astronautica 81 (2012) 288–305; the project's
//! `spec/MODEL.md` fixes every convention).
//!
//! ```text
//! M(y)·ẇ = −Ṁ·w − f1 + f2 + Q        (eq. 25)
//! ẋ      = B(x)·w                    (eq. 10, 24)
//! ```
//! x = [X, Y, Z, φ, θ, ψ, y1 … ym], w = [vx, vy, vz, Ωx, Ωy, Ωz, ẏ1 … ẏm].
//!
//! The crate is `#![no_std]`. Without features it holds the [`Scalar`] trait
//! and the [`Plant`] trait that a generated, allocation-free plant
//! implements; with `alloc` (default) it also holds the numeric [`Model`] and
//! the equations, written once, generic over the scalar, so that the generic
//! plant runs them with `f64` and the code generator traces them.
#![no_std]
#![warn(missing_docs)]

#[cfg(feature = "alloc")]
extern crate alloc;
#[cfg(feature = "std")]
extern crate std;

pub mod attitude;
pub mod cpu;
pub mod described;
pub mod dual;
pub mod linalg;
pub mod plant;
pub mod scalar;

#[cfg(feature = "alloc")]
pub mod model;
#[cfg(feature = "alloc")]
pub mod poly;

/// The nalgebra this crate's fixed-size types come from, so that generated
/// code and its users name one version.
pub use nalgebra;
pub use described::Described;
pub use plant::{FixedPlant, Plant};
pub use scalar::Scalar;

#[cfg(feature = "alloc")]
pub use model::Model;

#[cfg(feature = "alloc")]
pub mod bias;
#[cfg(feature = "alloc")]
pub mod eom;
#[cfg(feature = "alloc")]
pub mod fidelity;
#[cfg(feature = "alloc")]
pub mod forces;
#[cfg(feature = "alloc")]
pub mod kinematics;
#[cfg(feature = "alloc")]
pub mod mass;
#[cfg(feature = "alloc")]
pub mod solve;
#[cfg(feature = "alloc")]
pub mod workspace;
