//! A type that carries the rover description it was generated from.
//!
//! `#[derive(Rover)]` implements [`Described`] for the struct it is put on
//! and for its companion plant, so that one declaration gives both the fast
//! plant and everything the runtime needs besides it (the wheels' radii and
//! tyres for the contact, the motors' limits for the controllers, the rest
//! configuration for the initial state). The description is kept as the
//! text the derive validated; `rover-runtime` parses it again into the same
//! model (`rover_runtime::RoverDescription`), so the plant and the model
//! come from one source and cannot disagree.
//!
//! Nothing here allocates or parses: the trait is only constants, so a
//! `no_std` firmware build that uses the plant alone pays nothing for it.

/// A rover type generated from a description, carrying that description.
pub trait Described {
    /// The generated plant type.
    type Plant;
    /// The rover's name in its description.
    const NAME: &'static str;
    /// The description as TOML text (docs/DESCRIPTION.md): the file's text
    /// for `#[rover(file = "…")]`, or the attribute's fields written as
    /// TOML for an inline description.
    const DESCRIPTION: &'static str;
    /// Where the description was written, for messages: the file's path
    /// relative to the crate's `Cargo.toml`, or the source file of the
    /// struct with an inline description.
    const ORIGIN: &'static str;
    /// The fidelity level the plant was generated at: `"full"`,
    /// `"simplified"` or `"linearized"` (MODEL.md §9).
    const FIDELITY: &'static str;
    /// Where a reduced level is frozen, one value per suspension
    /// coordinate (rad or m); empty for the full model.
    const Y_REF: &'static [f64];
    /// A plant with the description's spring neutrals.
    fn plant() -> Self::Plant;
}

/// What the error stub of `#[derive(Rover)]` returns for a Jacobian, whose
/// size it does not know: it indexes like the real one (`jac[i][j]`,
/// `jac[(i, j)]`), so the code using it adds no error of its own to the
/// description's. It never runs (the crate with the stub does not compile).
#[doc(hidden)]
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct StubMatrix;

/// A row of [`StubMatrix`].
#[doc(hidden)]
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct StubRow;

impl core::ops::Index<usize> for StubMatrix {
    type Output = StubRow;
    fn index(&self, _: usize) -> &StubRow {
        &StubRow
    }
}

impl core::ops::Index<(usize, usize)> for StubMatrix {
    type Output = f64;
    fn index(&self, _: (usize, usize)) -> &f64 {
        &0.0
    }
}

impl core::ops::Index<usize> for StubRow {
    type Output = f64;
    fn index(&self, _: usize) -> &f64 {
        &0.0
    }
}
