//! The interface every wheel law implements, and the choice a scenario makes.
//! The equations themselves live in [`rover_dynamics::wheel_law`], generic
//! over the scalar, so that a run evaluates them and an implicit integrator
//! differentiates them from one copy.

use rover_dynamics::Scalar;
use rover_dynamics::wheel_law::{Lateral, patch_forces};
use serde::{Deserialize, Serialize};

pub use rover_dynamics::wheel_law::{PatchForces, PatchMotion, Tyre};

use super::{ChenGenta, MagicFormula};

/// A wheel–ground force law. Laws that need the wheel spin as a degree of
/// freedom (Bekker–Wong with Janosi–Hanamoto shear) will need more state;
/// this interface covers the rigid-spin laws of the paper and the magic formula.
pub trait WheelLaw {
    /// The lateral law and its constants.
    fn lateral(&self) -> Lateral;

    /// The forces on a patch, for any scalar: `f64` in a run, dual numbers
    /// for the derivatives an implicit integrator's Jacobian needs.
    fn forces<S: Scalar + PartialOrd>(
        &self,
        tyre: &Tyre,
        motion: &PatchMotion<S>,
    ) -> PatchForces<S> {
        patch_forces(&self.lateral(), tyre, motion)
    }
}

/// Which law a scenario uses (`wheel_law = { kind = "chen_genta" }`).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(tag = "kind", rename_all = "snake_case", deny_unknown_fields)]
pub enum WheelLawConfig {
    /// The paper's law (default).
    ChenGenta(ChenGenta),
    /// Pacejka's magic formula for the lateral force.
    MagicFormula(MagicFormula),
}

impl Default for WheelLawConfig {
    fn default() -> Self {
        WheelLawConfig::ChenGenta(ChenGenta::default())
    }
}

impl WheelLaw for WheelLawConfig {
    fn lateral(&self) -> Lateral {
        match self {
            WheelLawConfig::ChenGenta(l) => l.lateral(),
            WheelLawConfig::MagicFormula(l) => l.lateral(),
        }
    }
}
