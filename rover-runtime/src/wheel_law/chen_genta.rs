//! The paper's wheel law (MODEL.md §7, eq. 36–41).

use rover_dynamics::wheel_law::{Lateral, WheelLaw};
use serde::{Deserialize, Serialize};

/// Chen & Genta's law: spring–damper normal force, torque-limited drawbar
/// pull, exponential cornering force, elliptic combined slip
/// ([`rover_dynamics::wheel_law::patch_forces`]).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ChenGenta {
    /// Speed below which the sideslip angle is regularized [m/s]:
    /// `α = atan2(V_c, max(|V_t|, v_ε))`. At standstill α is undefined; 1e-3
    /// m/s is well below the paper's slowest run (0.05 m/s) yet keeps the
    /// lateral force of a parked rover a stiff, finite damper instead of a
    /// discontinuous sign.
    #[serde(default = "default_v_eps")]
    pub v_eps: f64,
}

fn default_v_eps() -> f64 {
    1e-3
}

impl Default for ChenGenta {
    fn default() -> Self {
        Self {
            v_eps: default_v_eps(),
        }
    }
}

impl WheelLaw for ChenGenta {
    fn lateral(&self) -> Lateral {
        Lateral::Exponential { v_eps: self.v_eps }
    }
}
