//! Pacejka's magic formula for the lateral force, as a second law (MODEL.md §7).

use rover_dynamics::wheel_law::{Lateral, WheelLaw};
use serde::{Deserialize, Serialize};

/// Normal and drive forces as in the paper; the lateral force by
/// ```text
/// F_c = −D·sin(C_s·atan(B·α − E·(B·α − atan(B·α)))),  D = μy·F_n,  B = C/(C_s·D)
/// ```
/// so that the slope at α = 0 is the wheel's cornering stiffness C, like eq. 40
/// ([`rover_dynamics::wheel_law::magic_formula`]).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MagicFormula {
    /// Shape factor C_s (1.3 is typical for lateral force).
    #[serde(default = "default_shape")]
    pub shape: f64,
    /// Curvature factor E (≤ 1).
    #[serde(default)]
    pub curvature: f64,
    /// Standstill regularization speed [m/s] (see [`super::ChenGenta::v_eps`]).
    #[serde(default = "default_v_eps")]
    pub v_eps: f64,
}

fn default_shape() -> f64 {
    1.3
}
fn default_v_eps() -> f64 {
    1e-3
}

impl Default for MagicFormula {
    fn default() -> Self {
        Self {
            shape: default_shape(),
            curvature: 0.0,
            v_eps: default_v_eps(),
        }
    }
}

impl WheelLaw for MagicFormula {
    fn lateral(&self) -> Lateral {
        Lateral::MagicFormula {
            shape: self.shape,
            curvature: self.curvature,
            v_eps: self.v_eps,
        }
    }
}
