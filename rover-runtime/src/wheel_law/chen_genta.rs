//! The paper's wheel law (MODEL.md §7, eq. 36–41).

use serde::{Deserialize, Serialize};

use super::law::{PatchForces, PatchMotion, Tyre, WheelLaw, combined, drawbar_pull, normal_force};

/// Chen & Genta's law: spring–damper normal force, torque-limited drawbar
/// pull, exponential cornering force, elliptic combined slip.
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

/// Sideslip angle α between the heading t and the centre's velocity,
/// regularized at standstill: `α = atan2(V_c, max(|V_t|, v_ε))` \[rad\].
pub fn sideslip(motion: &PatchMotion, v_eps: f64) -> f64 {
    motion.v_c.atan2(motion.v_t.abs().max(v_eps))
}

/// Cornering force on one patch (MODEL.md §7, paper eq. 40).
/// ```text
/// F_c = −μy·F_n·sgn(α)·(1 − exp(−C·|α| / (μy·F_n)))
/// ```
/// α sideslip \[rad\], F_n normal force \[N\] (> 0), C cornering stiffness [N/rad].
/// Positive result points along c = n × t, i.e. to the wheel's left; it
/// opposes the sideslip.
pub fn cornering_force(tyre: &Tyre, normal: f64, alpha: f64) -> f64 {
    let cap = tyre.mu_y * normal;
    -cap * alpha.signum() * (1.0 - (-tyre.cornering_stiffness * alpha.abs() / cap).exp())
}

impl WheelLaw for ChenGenta {
    fn forces(&self, tyre: &Tyre, motion: &PatchMotion) -> PatchForces {
        let normal = normal_force(tyre, motion);
        if normal <= 0.0 {
            return PatchForces::default();
        }
        let drawbar = drawbar_pull(tyre, motion, normal);
        let lateral = cornering_force(tyre, normal, sideslip(motion, self.v_eps));
        PatchForces {
            normal,
            drawbar,
            lateral: combined(lateral, drawbar, tyre, normal),
        }
    }
}
