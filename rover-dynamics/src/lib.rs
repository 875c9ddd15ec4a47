//! The equations of motion of a wheeled rover in pseudo-coordinates
//! (F. Chen and G. Genta, Acta Astronautica 81 (2012) 288–305; the
//! repository's `docs/MODEL.md` fixes every convention).
//!
//! ```text
//! M(y)·ẇ = −Ṁ·w − f1 + f2 + Q        (eq. 25)
//! ẋ      = B(x)·w                    (eq. 10, 24)
//! ```
//! x = [X, Y, Z, φ, θ, ψ, y1 … ym], w = [vx, vy, vz, Ωx, Ωy, Ωz, ẏ1 … ẏm].
//!
//! The crate is `#![no_std]`. Its features (both default):
//! - `plant`: the [`Plant`] and [`FixedPlant`] traits that a generated,
//!   allocation-free plant implements (with nalgebra for the fixed-size
//!   types). A firmware crate using a generated plant takes
//!   `default-features = false, features = ["plant"]`.
//! - `alloc`: the numeric [`Model`] and the equations, written once,
//!   generic over the scalar, so that the generic plant runs them with
//!   `f64` and the code generator traces them. The code generator needs
//!   only this one, which keeps nalgebra out of what `#[derive(Rover)]`
//!   compiles for the compiler's host.
//!
//! Without features it still has the wheel–ground law ([`wheel_law`]),
//! the contact search ([`contact`]) and the height-field interface it
//! queries ([`HeightField`]), so that code outside `std` can use them;
//! with `plant`, the ground acting on a wheel ([`wheel_ground`]): the
//! search, the law and the reduction to loads that the runtime and a
//! generated plant's own force path both run. Its `std` feature only
//! takes the contact search's elementary functions from the platform
//! instead of `libm` (the runtime's build); `serde` derives the choice of
//! search for scenario files.
#![no_std]
#![warn(missing_docs)]

#[cfg(feature = "alloc")]
extern crate alloc;
#[cfg(feature = "std")]
extern crate std;

pub mod attitude;
pub mod bicubic;
pub mod contact;
pub mod cpu;
pub mod described;
pub mod dual;
pub mod height_field;
pub mod linalg;
#[cfg(feature = "plant")]
pub mod plant;
pub mod scalar;
pub mod soil;
#[cfg(feature = "plant")]
pub mod wheel_ground;
pub mod wheel_law;
#[cfg(feature = "plant")]
pub mod wheel_soil;

#[cfg(feature = "alloc")]
pub mod model;
#[cfg(feature = "alloc")]
pub mod poly;

pub use described::Described;
pub use height_field::HeightField;
/// The nalgebra this crate's fixed-size types come from, so that generated
/// code and its users name one version.
#[cfg(feature = "plant")]
pub use nalgebra;
#[cfg(feature = "plant")]
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
