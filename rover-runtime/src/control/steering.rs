//! Kinematic (Ackermann) and slip steering (MODEL.md §8, paper eq. 45–48).

use serde::{Deserialize, Serialize};

use super::Profile;

/// How the rover steers.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(tag = "kind", rename_all = "snake_case", deny_unknown_fields)]
pub enum Steering {
    /// Straight ahead, no steering.
    #[default]
    None,
    /// Kinematic steering of the steerable wheels (eq. 45–46 as special
    /// cases of the general formula).
    Ackermann(Ackermann),
    /// Skid steering by a torque difference (eq. 48):
    /// `τ_L = τ_0 − Δτ`, `τ_R = τ_0 + Δτ`; Δτ > 0 turns left.
    Slip {
        /// Δτ [N·m] against time after settling.
        delta_tau: Profile,
    },
}

/// Ackermann steering: the turn centre at body point (x_c, R).
/// ```text
/// δ_j = atan(κ·(x_j − x_c) / (1 − κ·y_j)),  κ = 1/R
/// ```
/// Give either the turning radius or the front-left wheel's angle.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Ackermann {
    /// Lateral position R of the turn centre \[m\], R > 0 turns left
    /// (the kinematic radius is `sqrt(x_c² + R²)`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub radius: Option<Profile>,
    /// Steering angle of the first steerable wheel \[deg\] (eq. 46's δ_1),
    /// converted to κ with the general formula.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub front_left_deg: Option<Profile>,
    /// Longitudinal position x_c of the turn centre \[m\]. Default: the mean
    /// rest x of the non-steerable wheels, or when all steer, the rest x of
    /// the wheel nearest to G along x (the middle axle of a 6-wheeler).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub centre_x: Option<f64>,
}

/// Curvature κ from the first steerable wheel's angle δ_1 at rest position
/// (x_1, y_1): inverting `tan δ_1 = κ·(x_1 − x_c)/(1 − κ·y_1)`.
pub fn curvature_from_angle(delta1: f64, x1: f64, y1: f64, xc: f64) -> f64 {
    let t = delta1.tan();
    t / ((x1 - xc) + y1 * t)
}

/// Steering angle of a wheel at rest position (x, y) for curvature κ.
pub fn ackermann_angle(kappa: f64, x: f64, y: f64, xc: f64) -> f64 {
    (kappa * (x - xc)).atan2(1.0 - kappa * y)
}
