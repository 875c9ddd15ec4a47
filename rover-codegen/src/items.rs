//! The items a generated plant type offers its users: one table, read by
//! the generator ([`crate::plant_source()`] emits each item), by the
//! derive's stand-in for an invalid description (which mirrors each item,
//! so that the code using the rover still type-checks and the description's
//! error is the only one) and by the tests that hold both to it.
//!
//! The generator and the stand-in match on [`Item`] without a wildcard: an
//! item added here is an item both must write.

/// What an item is.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Kind {
    /// An associated constant of the plant type.
    Const,
    /// An associated function or method of the plant type.
    Method,
    /// An implementation of a trait for the plant type.
    Impl,
}

/// The table: each item's variant, documentation, kind and Rust name, in
/// the order of the generated code.
macro_rules! items {
    ($($(#[$doc:meta])* $item:ident: $kind:ident $name:literal,)*) => {
        /// A public item of a generated plant type.
        #[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
        pub enum Item {
            $($(#[$doc])* $item,)*
        }

        impl Item {
            /// Every item, in the order of the generated code.
            pub const ALL: &'static [Item] = &[$(Item::$item,)*];

            /// The item's name in Rust: the constant's, the function's, or
            /// the trait's (its last path segment).
            pub const fn name(self) -> &'static str {
                match self {
                    $(Item::$item => $name,)*
                }
            }

            /// What the item is.
            pub const fn kind(self) -> Kind {
                match self {
                    $(Item::$item => Kind::$kind,)*
                }
            }
        }
    };
}

items! {
    /// `Default`, the plant with the description's spring neutrals.
    Default: Impl "Default",
    /// The rover's name in its description.
    Name: Const "NAME",
    /// The number of generalized coordinates N = 6 + m.
    Dof: Const "DOF",
    /// The number of wheels.
    Wheels: Const "WHEELS",
    /// The names of the suspension coordinates.
    Coordinates: Const "COORDINATES",
    /// The names of the wheels.
    WheelNames: Const "WHEEL_NAMES",
    /// The description's spring neutrals y_0.
    SpringNeutrals: Const "SPRING_NEUTRALS",
    /// The smallest |cos φ| accepted, as the generic plant's.
    MinCosRoll: Const "MIN_COS_ROLL",
    /// `new()`, a `const fn`.
    New: Method "new",
    /// The current spring neutrals.
    CurrentNeutrals: Method "spring_neutrals",
    /// `ẋ` and `ẇ` on plain arrays.
    DerivativesArray: Method "derivatives_array",
    /// `derivatives_array` for the crate's own target only (hidden).
    DerivativesPortable: Method "derivatives_portable",
    /// The mass matrix on plain arrays.
    MassMatrixArray: Method "mass_matrix_array",
    /// The wheels' kinematics on plain arrays.
    WheelsArray: Method "wheels_array",
    /// The exact Jacobian on plain arrays (with the Jacobian only).
    JacobianArray: Method "jacobian_array",
    /// The exact Jacobian as a nalgebra matrix (with the Jacobian only).
    JacobianFixed: Method "jacobian_fixed",
    /// Each wheel's tyre.
    Tyres: Const "TYRES",
    /// Each wheel's radius.
    Radii: Const "RADII",
    /// The ground state of the force path.
    Ground: Method "ground",
    /// The whole right-hand side on a height field.
    DerivativesOnGround: Method "derivatives_on_ground",
    /// `rover_dynamics::plant::Plant`, the slice interface.
    Plant: Impl "Plant",
    /// `rover_dynamics::plant::FixedPlant`, the nalgebra interface.
    FixedPlant: Impl "FixedPlant",
}

impl Item {
    /// Whether the item exists only when the exact Jacobian is generated.
    pub const fn needs_jacobian(self) -> bool {
        matches!(self, Item::JacobianArray | Item::JacobianFixed)
    }

    /// [`Item::ALL`] in the blocks of the generated code: each trait
    /// implementation alone, and the constants and methods in a row
    /// together, as one inherent `impl` block.
    pub fn blocks() -> impl Iterator<Item = &'static [Item]> {
        Item::ALL.chunk_by(|a, b| a.kind() != Kind::Impl && b.kind() != Kind::Impl)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn each_item_is_listed_once_under_its_own_name() {
        let mut names: Vec<&str> = Item::ALL.iter().map(|i| i.name()).collect();
        names.sort_unstable();
        names.dedup();
        assert_eq!(names.len(), Item::ALL.len());
    }

    #[test]
    fn blocks_are_a_trait_impl_each_and_the_runs_of_members() {
        let blocks: Vec<&[Item]> = Item::blocks().collect();
        assert_eq!(blocks.len(), 4);
        assert_eq!(blocks[0], [Item::Default]);
        assert_eq!(blocks[1].first(), Some(&Item::Name));
        assert_eq!(blocks[1].last(), Some(&Item::DerivativesOnGround));
        assert_eq!(blocks[2..], [&[Item::Plant][..], &[Item::FixedPlant][..]]);
        assert_eq!(blocks.concat(), Item::ALL);
    }
}
