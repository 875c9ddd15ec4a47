//! The wheel–ground force law on one contact patch (MODEL.md §7, paper
//! eq. 36–41), written once, generic over the scalar: runs evaluate it with
//! `f64`, and implicit integrators differentiate the very same code with
//! [`Dual`](crate::dual::Dual) numbers for their Jacobian.
//!
//! Everything here is a function of the patch's motion in its own frame
//! (n, t, c) and of the tyre's constants; how the patches are found and how
//! their forces reduce to the wheel centre is the runtime's business.

use crate::scalar::Scalar;

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
pub struct PatchMotion<S = f64> {
    /// Radial deflection Δ \[m\].
    pub deflection: S,
    /// Deflection rate Δ̇ = −V_j·n [m/s].
    pub deflection_rate: S,
    /// Velocity of the wheel centre along t [m/s].
    pub v_t: S,
    /// Velocity of the wheel centre along c [m/s].
    pub v_c: S,
    /// Lever arm |G_jH| \[m\].
    pub lever: S,
    /// Drive torque assigned to this patch [N·m].
    pub torque: S,
}

/// Forces on one patch, in its frame: `F = F_n·n + F_d·t + F_c·c`.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct PatchForces<S = f64> {
    /// Normal force F_n ≥ 0 \[N\].
    pub normal: S,
    /// Drawbar pull F_d along t, after saturation \[N\].
    pub drawbar: S,
    /// Lateral force along c, after combined slip \[N\].
    pub lateral: S,
}

/// Which lateral law a patch follows, with its constants.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Lateral {
    /// The paper's exponential cornering force (eq. 40); `v_eps` regularizes
    /// the sideslip at standstill ([`sideslip`]).
    Exponential {
        /// Regularization speed [m/s].
        v_eps: f64,
    },
    /// Pacejka's magic formula with shape factor C_s and curvature E, its
    /// slope at α = 0 the cornering stiffness C.
    MagicFormula {
        /// Shape factor C_s.
        shape: f64,
        /// Curvature factor E (≤ 1).
        curvature: f64,
        /// Regularization speed [m/s].
        v_eps: f64,
    },
}

/// Depth over which the tyre damper ramps in \[m\]. Eq. 37's damper acting in
/// full at the first touch makes the normal force jump from 0 to c_w·Δ̇ when
/// a wheel lands, a discontinuity that stalls step-size control (a rover
/// hopping at 1 m/s on rough ground did). Ramping the damper in over the
/// first 0.1 mm — 1/20 of the paper rovers' static deflection (≈ 2.2 mm) —
/// keeps the force continuous and leaves eq. 37 exact beyond it.
pub const DAMPING_RAMP: f64 = 1e-4;

/// Speed below which the rolling resistance is regularized [m/s]: its
/// direction is `v_t/sqrt(v_t² + v_ε²)`, the sign of the rolling speed made
/// continuous (a sign would jump at standstill and stall step-size
/// control), as the sideslip is at the same 1 mm/s.
pub const ROLLING_V_EPS: f64 = 1e-3;

/// Normal force (eq. 36–37): `F_n = max(0, k_w·Δ + c_w·Δ̇·min(1, Δ/Δ_c))` —
/// the ground never pulls; Δ_c = [`DAMPING_RAMP`].
pub fn normal_force<S: Scalar>(tyre: &Tyre, motion: &PatchMotion<S>) -> S {
    let ramp = (motion.deflection / S::cst(DAMPING_RAMP))
        .max(S::zero())
        .min(S::one());
    (S::cst(tyre.stiffness) * motion.deflection
        + S::cst(tyre.damping) * motion.deflection_rate * ramp)
        .max(S::zero())
}

/// Rolling resistance along t (ours, not the paper's):
/// `F_rr = −C_rr·F_n·v_t/sqrt(v_t² + v_ε²)`, a ground force against the
/// wheel's rolling, on top of the drawbar pull and not through the motor
/// (its moment about the axle is the soil's, like the pressure offset it
/// stands for: the carrier does not receive it, the stator neither). Exactly
/// 0 when C_rr = 0. A rover parked on a slope below atan(C_rr) creeps at
/// about `v_ε·tan α/sqrt(C_rr² − tan² α)` instead of standing still.
pub fn rolling_resistance<S: Scalar>(tyre: &Tyre, motion: &PatchMotion<S>, normal: S) -> S {
    if tyre.rolling_resistance == 0.0 {
        return S::zero();
    }
    S::cst(-tyre.rolling_resistance) * normal * motion.v_t / motion.v_t.hypot(S::cst(ROLLING_V_EPS))
}

/// Drawbar pull (eq. 38–39): `F_d = τ/|G_jH|`, saturated at `|F_d| ≤ μx_max·F_n`.
pub fn drawbar_pull<S: Scalar>(tyre: &Tyre, motion: &PatchMotion<S>, normal: S) -> S {
    let limit = S::cst(tyre.mu_x) * normal;
    (motion.torque / motion.lever).max(-limit).min(limit)
}

/// Combined slip (eq. 41): `F_c* = F_c·sqrt(1 − (|F_d|/(μx_max·F_n))²)`.
pub fn combined<S: Scalar>(lateral: S, drawbar: S, tyre: &Tyre, normal: S) -> S {
    let ratio = (drawbar.abs() / (S::cst(tyre.mu_x) * normal)).min(S::one());
    lateral * (S::one() - ratio * ratio).sqrt()
}

/// Sideslip angle α between the heading t and the centre's velocity,
/// regularized at standstill: `α = atan2(V_c, max(|V_t|, v_ε))` \[rad\].
pub fn sideslip<S: Scalar>(motion: &PatchMotion<S>, v_eps: f64) -> S {
    motion.v_c.atan2(motion.v_t.abs().max(S::cst(v_eps)))
}

/// Cornering force on one patch (MODEL.md §7, paper eq. 40).
/// ```text
/// F_c = −μy·F_n·sgn(α)·(1 − exp(−C·|α| / (μy·F_n)))
/// ```
/// α sideslip \[rad\], F_n normal force \[N\] (> 0), C cornering stiffness [N/rad].
/// Positive result points along c = n × t, i.e. to the wheel's left; it
/// opposes the sideslip.
pub fn cornering_force<S: Scalar>(tyre: &Tyre, normal: S, alpha: S) -> S {
    let cap = S::cst(tyre.mu_y) * normal;
    -cap * S::one().copysign(alpha)
        * (S::one() - (S::cst(-tyre.cornering_stiffness) * alpha.abs() / cap).exp())
}

/// The magic formula's lateral force,
/// ```text
/// F_c = −D·sin(C_s·atan(B·α − E·(B·α − atan(B·α)))),  D = μy·F_n,  B = C/(C_s·D)
/// ```
/// so that the slope at α = 0 is the wheel's cornering stiffness C, like eq. 40.
pub fn magic_formula<S: Scalar>(tyre: &Tyre, normal: S, alpha: S, shape: f64, curvature: f64) -> S {
    let d = S::cst(tyre.mu_y) * normal;
    let b = S::cst(tyre.cornering_stiffness) / (S::cst(shape) * d);
    let ba = b * alpha;
    -d * (S::cst(shape) * (ba - S::cst(curvature) * (ba - ba.atan())).atan()).sin()
}

/// The forces on one patch: eq. 36–41 with the lateral law `lateral`. A patch
/// that does not press on the ground (F_n = 0) carries no force at all.
pub fn patch_forces<S: Scalar + PartialOrd>(
    lateral: &Lateral,
    tyre: &Tyre,
    motion: &PatchMotion<S>,
) -> PatchForces<S> {
    let normal = normal_force(tyre, motion);
    if normal <= S::zero() {
        return PatchForces {
            normal: S::zero(),
            drawbar: S::zero(),
            lateral: S::zero(),
        };
    }
    let drawbar = drawbar_pull(tyre, motion, normal);
    let side = match *lateral {
        Lateral::Exponential { v_eps } => cornering_force(tyre, normal, sideslip(motion, v_eps)),
        Lateral::MagicFormula {
            shape,
            curvature,
            v_eps,
        } => magic_formula(tyre, normal, sideslip(motion, v_eps), shape, curvature),
    };
    PatchForces {
        normal,
        drawbar,
        lateral: combined(side, drawbar, tyre, normal),
    }
}

/// A wheel–ground force law. Laws that need the wheel spin as a degree of
/// freedom (Bekker–Wong with Janosi–Hanamoto shear) will need more state;
/// this interface covers the rigid-spin laws of the paper and the magic
/// formula. A [`Lateral`] is itself a law; the runtime's scenario laws
/// (`rover_runtime::wheel_law`) say which one from a file.
pub trait WheelLaw {
    /// The lateral law and its constants.
    fn lateral(&self) -> Lateral;

    /// The forces on a patch, for any scalar: `f64` in a run, dual numbers
    /// for the derivatives an implicit integrator's Jacobian needs.
    #[inline]
    fn forces<S: Scalar + PartialOrd>(
        &self,
        tyre: &Tyre,
        motion: &PatchMotion<S>,
    ) -> PatchForces<S> {
        patch_forces(&self.lateral(), tyre, motion)
    }
}

impl WheelLaw for Lateral {
    #[inline]
    fn lateral(&self) -> Lateral {
        *self
    }
}
