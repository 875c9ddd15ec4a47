//! Pacejka's magic formula for the lateral force, as a second law (MODEL.md §7).

use serde::{Deserialize, Serialize};

use super::chen_genta::sideslip;
use super::law::{PatchForces, PatchMotion, Tyre, WheelLaw, combined, drawbar_pull, normal_force};

/// Normal and drive forces as in the paper; the lateral force by
/// ```text
/// F_c = −D·sin(C_s·atan(B·α − E·(B·α − atan(B·α)))),  D = μy·F_n,  B = C/(C_s·D)
/// ```
/// so that the slope at α = 0 is the wheel's cornering stiffness C, like eq. 40.
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
    fn forces(&self, tyre: &Tyre, motion: &PatchMotion) -> PatchForces {
        let normal = normal_force(tyre, motion);
        if normal <= 0.0 {
            return PatchForces::default();
        }
        let drawbar = drawbar_pull(tyre, motion, normal);
        let alpha = sideslip(motion, self.v_eps);
        let d = tyre.mu_y * normal;
        let b = tyre.cornering_stiffness / (self.shape * d);
        let ba = b * alpha;
        let lateral = -d * (self.shape * (ba - self.curvature * (ba - ba.atan())).atan()).sin();
        PatchForces {
            normal,
            drawbar,
            lateral: combined(lateral, drawbar, tyre, normal),
        }
    }
}
