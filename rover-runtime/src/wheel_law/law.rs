//! The interface every wheel law implements.

use serde::{Deserialize, Serialize};

use super::{ChenGenta, MagicFormula};

/// The tyre parameters of one wheel (from the rover description).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Tyre {
    /// Radial stiffness k_w [N/m].
    pub stiffness: f64,
    /// Radial damping c_w [N·s/m].
    pub damping: f64,
    /// Longitudinal friction limit μx_max.
    pub mu_x: f64,
    /// Lateral friction limit μy_max.
    pub mu_y: f64,
    /// Cornering stiffness C [N/rad].
    pub cornering_stiffness: f64,
    /// Rolling-resistance coefficient C_rr (a scenario's
    /// `contact.rolling_resistance`; 0 in the paper).
    pub rolling_resistance: f64,
}

/// The motion of one patch, in its own frame (n, t, c).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PatchMotion {
    /// Radial deflection Δ \[m\].
    pub deflection: f64,
    /// Deflection rate Δ̇ = −V_j·n [m/s].
    pub deflection_rate: f64,
    /// Velocity of the wheel centre along t [m/s].
    pub v_t: f64,
    /// Velocity of the wheel centre along c [m/s].
    pub v_c: f64,
    /// Lever arm |G_jH| \[m\].
    pub lever: f64,
    /// Drive torque assigned to this patch [N·m].
    pub torque: f64,
}

/// Forces on one patch, in its frame: `F = F_n·n + F_d·t + F_c·c`.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct PatchForces {
    /// Normal force F_n ≥ 0 \[N\].
    pub normal: f64,
    /// Drawbar pull F_d along t, after saturation \[N\].
    pub drawbar: f64,
    /// Lateral force along c, after combined slip \[N\].
    pub lateral: f64,
}

/// A wheel–ground force law. Laws that need the wheel spin as a degree of
/// freedom (Bekker–Wong with Janosi–Hanamoto shear) will need more state;
/// this interface covers the rigid-spin laws of the paper and the magic formula.
pub trait WheelLaw {
    /// The forces on a patch.
    fn forces(&self, tyre: &Tyre, motion: &PatchMotion) -> PatchForces;
}

/// Depth over which the tyre damper ramps in \[m\]. Eq. 37's damper acting in
/// full at the first touch makes the normal force jump from 0 to c_w·Δ̇ when
/// a wheel lands, a discontinuity that stalls step-size control (a rover
/// hopping at 1 m/s on rough ground did). Ramping the damper in over the
/// first 0.1 mm — 1/20 of the paper rovers' static deflection (≈ 2.2 mm) —
/// keeps the force continuous and leaves eq. 37 exact beyond it.
pub const DAMPING_RAMP: f64 = 1e-4;

/// Normal force (eq. 36–37): `F_n = max(0, k_w·Δ + c_w·Δ̇·min(1, Δ/Δ_c))` —
/// the ground never pulls; Δ_c = [`DAMPING_RAMP`].
pub fn normal_force(tyre: &Tyre, motion: &PatchMotion) -> f64 {
    let ramp = (motion.deflection / DAMPING_RAMP).clamp(0.0, 1.0);
    (tyre.stiffness * motion.deflection + tyre.damping * motion.deflection_rate * ramp).max(0.0)
}

/// Speed below which the rolling resistance is regularized [m/s]: its
/// direction is `v_t/sqrt(v_t² + v_ε²)`, the sign of the rolling speed made
/// continuous (a sign would jump at standstill and stall step-size
/// control), as the sideslip is at the same 1 mm/s.
pub const ROLLING_V_EPS: f64 = 1e-3;

/// Rolling resistance along t (ours, not the paper's):
/// `F_rr = −C_rr·F_n·v_t/sqrt(v_t² + v_ε²)`, a ground force against the
/// wheel's rolling, on top of the drawbar pull and not through the motor
/// (its moment about the axle is the soil's, like the pressure offset it
/// stands for: the carrier does not receive it, the stator neither). Exactly
/// 0 when C_rr = 0. A rover parked on a slope below atan(C_rr) creeps at
/// about `v_ε·tan α/sqrt(C_rr² − tan² α)` instead of standing still.
pub fn rolling_resistance(tyre: &Tyre, motion: &PatchMotion, normal: f64) -> f64 {
    if tyre.rolling_resistance == 0.0 {
        return 0.0;
    }
    -tyre.rolling_resistance * normal * motion.v_t / motion.v_t.hypot(ROLLING_V_EPS)
}

/// Drawbar pull (eq. 38–39): `F_d = τ/|G_jH|`, saturated at `|F_d| ≤ μx_max·F_n`.
pub fn drawbar_pull(tyre: &Tyre, motion: &PatchMotion, normal: f64) -> f64 {
    let limit = tyre.mu_x * normal;
    (motion.torque / motion.lever).clamp(-limit, limit)
}

/// Combined slip (eq. 41): `F_c* = F_c·sqrt(1 − (|F_d|/(μx_max·F_n))²)`.
pub fn combined(lateral: f64, drawbar: f64, tyre: &Tyre, normal: f64) -> f64 {
    let ratio = (drawbar.abs() / (tyre.mu_x * normal)).min(1.0);
    lateral * (1.0 - ratio * ratio).sqrt()
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
    fn forces(&self, tyre: &Tyre, motion: &PatchMotion) -> PatchForces {
        match self {
            WheelLawConfig::ChenGenta(l) => l.forces(tyre, motion),
            WheelLawConfig::MagicFormula(l) => l.forces(tyre, motion),
        }
    }
}
