//! `#[derive(Rover)]`: a rover description becomes a specialized plant type
//! at compile time. A thin shell over [`rover_codegen::expand_derive`]
//! (STYLE.md §2); docs/CODEGEN.md is the manual.
//!
//! ```ignore
//! use rover_derive::Rover;
//!
//! #[derive(Rover)]
//! #[rover(file = "models/toy.toml")] // relative to this crate's Cargo.toml
//! pub struct Toy;
//!
//! let mut plant = Toy::plant(); // a `ToyPlant`: rover_dynamics::{Plant, FixedPlant<N, W>}
//! ```
//! The same description inline, as Rust tokens with the TOML fields:
//! `#[rover(name = "toy", gravity = 1.62, body = { mass = 30.0, inertia = [0.7, 0.9, 1.5] },
//! suspension = [{ … }], wheel = [{ … }])]`. Add `jacobian = true` for the exact
//! Jacobian `jacobian_fixed` (nalgebra) and `jacobian_array`. The crate using it needs `rover-dynamics`
//! (`default-features = false` is enough) and `libm`.
//!
//! Mistakes are compile errors at the offending token, or at the `file`
//! literal quoting `path:line:col` and the line of the TOML file.
#![warn(missing_docs)]

use proc_macro::TokenStream;

/// Generate `<Name>Plant`, the plant of the rover described in `#[rover(…)]`.
#[proc_macro_derive(Rover, attributes(rover))]
pub fn derive_rover(input: TokenStream) -> TokenStream {
    let input = syn::parse_macro_input!(input as syn::DeriveInput);
    rover_codegen::expand_derive(&input).into()
}
