//! The interface every wheel law implements, and the choice a scenario makes.
//! The equations themselves live in [`rover_dynamics::wheel_law`], generic
//! over the scalar, so that a run evaluates them and an implicit integrator
//! differentiates them from one copy.

use rover_dynamics::wheel_law::{Lateral, WheelLaw};
use serde::{Deserialize, Serialize};

use super::{ChenGenta, MagicFormula};

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
