//! `#[derive(Rover)]`: a rover description becomes a specialized plant type
//! at compile time, carrying the description it came from. A thin shell
//! over `rover_codegen::expand_derive`, an ordinary function that tests can
//! call; docs/CODEGEN.md is the manual.
//!
//! The description is written inline, as Rust tokens with the fields of the
//! TOML format (docs/DESCRIPTION.md; `[[suspension]]` tables become
//! `suspension = [{ … }, …]`), or as `#[rover(file = "my_rover.toml")]`,
//! relative to the crate's `Cargo.toml` (editing the file rebuilds).
//!
//! ```
//! use rover_derive::Rover;
//! use rover_runtime::RoverDescription;
//! use rover_scenario::Simulation;
//! use rover_runtime::terrain::TerrainConfig;
//!
//! #[derive(Rover)]
//! #[rover(
//!     name = "swing4", gravity = 1.62,
//!     body = { mass = 30.0, inertia = [0.7, 0.9, 1.5] },
//!     wheel_defaults = { mass = 0.6, radius = 0.09, stiffness = 4000.0, damping = 300.0,
//!         mu_x = 0.5, mu_y = 0.5, cornering_stiffness = 50.0, max_torque = 1.29 },
//!     suspension = [
//!         { name = "fl", kind = "longitudinal_swing_arm", pivot = [0.18, 0.2, -0.01], length = 0.2,
//!           coordinate = { rest_deg = -17.2, min_deg = -60.0, max_deg = -2.0, stiffness = 5.0, damping = 3.5 } },
//!         { name = "fr", kind = "longitudinal_swing_arm", pivot = [0.18, -0.2, -0.01], length = 0.2,
//!           coordinate = { rest_deg = -17.2, min_deg = -60.0, max_deg = -2.0, stiffness = 5.0, damping = 3.5 } },
//!         { name = "rl", kind = "longitudinal_swing_arm", pivot = [-0.22, 0.2, -0.01], length = 0.2,
//!           coordinate = { rest_deg = 17.2, min_deg = 2.0, max_deg = 60.0, stiffness = 5.0, damping = 3.5 } },
//!         { name = "rr", kind = "longitudinal_swing_arm", pivot = [-0.22, -0.2, -0.01], length = 0.2,
//!           coordinate = { rest_deg = 17.2, min_deg = 2.0, max_deg = 60.0, stiffness = 5.0, damping = 3.5 } },
//!     ],
//!     wheel = [
//!         { name = "fl", suspension = "fl" }, { name = "fr", suspension = "fr" },
//!         { name = "rl", suspension = "rl" }, { name = "rr", suspension = "rr" },
//!     ],
//! )]
//! pub struct Swing4;
//!
//! // The plant: `Swing4Plant`, implementing rover_dynamics::{Plant, FixedPlant<10, 4>}.
//! let plant = Swing4::plant();
//! assert_eq!((Swing4Plant::DOF, Swing4Plant::WHEELS), (10, 4));
//!
//! // The rover inspected: what `rover check` prints for a file.
//! assert!(Swing4::report()?.starts_with("rover `swing4`: 10 DOF"));
//!
//! // And run: the model of the terrain contact and the controllers comes
//! // from the plant's own description.
//! let summary = Simulation::new(plant)
//!     .terrain(TerrainConfig::random(0.1))
//!     .settle(1.0)
//!     .speed(0.1)
//!     .run(2.0)?;
//! assert!(summary.complete);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
//!
//! What it generates, next to the struct `Swing4`:
//! - `Swing4Plant`, the plant: straight-line code with the rover's numbers
//!   folded in, no heap, `no_std`; the slice API of
//!   `rover_dynamics::Plant`, the nalgebra API of `FixedPlant<N, W>` and
//!   plain arrays (`derivatives_array`, `mass_matrix_array`, `wheels_array`);
//!   the constants `NAME`, `DOF`, `WHEELS`, `COORDINATES`, `WHEEL_NAMES`,
//!   `SPRING_NEUTRALS`;
//! - `Swing4::plant()`;
//! - `rover_dynamics::Described` for both types: the description as TOML
//!   text (`DESCRIPTION`), where it was written, the fidelity level. With
//!   it, `rover_runtime::RoverDescription` gives `spec()`, `model()` and
//!   `report()`, and `rover_scenario::Simulation::new` runs the plant alone.
//!
//! Options in the attribute: `jacobian = true` adds the exact Jacobian
//! (`jacobian_array`, `jacobian_fixed`); `fidelity = "simplified"`,
//! `"linearized"` or `"linearized_exact_rotation"` generates a reduced level
//! (MODEL.md §9), frozen at
//! `y_ref = [...]` or at the description's rest configuration.
//!
//! The crate using it depends on `rover-derive`, `rover-runtime` and
//! `rover-scenario` (the README's three lines), and on nothing else for
//! the generated code, which names `rover_dynamics` and `libm` through
//! `rover_runtime`. In `no_std` firmware, without the runtime, it depends
//! on `rover-derive`, `rover-dynamics = { default-features = false,
//! features = ["plant"] }` and `libm`, and writes `no_std = true` in the
//! attribute: the code then names those two crates directly.
//!
//! Values in the attribute are literals: the description is validated and
//! the plant generated while the crate compiles, before constants and
//! expressions have values, so `mass = MASS` is a compile error at `MASS`.
//! A rover whose numbers come from Rust is built at run time instead
//! (docs/RUST.md, "A rover built at run time").
//!
//! What the derive costs to build: it runs the code generator at compile
//! time, so the generator and what it needs (rover-spec with serde and
//! toml, rover-dynamics' equations, syn) are compiled once more, for the
//! compiler's host; nalgebra, the formatter of `rover codegen` and
//! thiserror are kept out of that build. Expanding one rover takes a
//! fraction of a second.
//!
//! Mistakes are compile errors at the offending token, or at the `file`
//! literal quoting `path:line:col` and the line of the TOML file; one
//! mistake is one error: next to it the derive emits a stand-in with every
//! item of the plant, so that the code using the rover adds none.
#![warn(missing_docs)]

use proc_macro::TokenStream;

/// Generate `<Name>Plant`, the plant of the rover described in
/// `#[rover(…)]`, and the description it carries (see the crate docs).
#[proc_macro_derive(Rover, attributes(rover))]
pub fn derive_rover(input: TokenStream) -> TokenStream {
    let input = syn::parse_macro_input!(input as syn::DeriveInput);
    rover_codegen::expand_derive(&input).into()
}
