//! Active suspension (MODEL.md §8, paper eq. 42, §5.2).

use serde::{Deserialize, Serialize};

/// Every `sample_time` the pitch θ and roll φ and their Euler rates are
/// measured and the spring neutrals corrected:
/// ```text
/// y0 ← clamp(y0 + (K_p1·θ + K_d1·θ̇)·s_θ + (K_p2·φ + K_d2·φ̇)·s_φ, y_min, y_max)
/// ```
/// The law is incremental — an integral controller; gains are per update.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ActiveSuspensionConfig {
    /// Update period Δt_c \[s\] (the paper's 0.1 s).
    #[serde(default = "default_sample")]
    pub sample_time: f64,
    /// Pitch gain K_p1 [rad of y0 per rad, per update].
    pub kp_pitch: f64,
    /// Pitch-rate gain K_d1 [rad of y0 per rad/s, per update].
    #[serde(default)]
    pub kd_pitch: f64,
    /// Roll gain K_p2.
    pub kp_roll: f64,
    /// Roll-rate gain K_d2.
    #[serde(default)]
    pub kd_roll: f64,
}

fn default_sample() -> f64 {
    0.1
}

/// The running law: gains, sign vectors and the neutrals it commands.
#[derive(Clone, Debug, PartialEq)]
pub struct ActiveSuspension {
    /// The configuration.
    pub config: ActiveSuspensionConfig,
    /// s_θ per coordinate (0 for coordinates without a spring).
    pub sign_pitch: Vec<f64>,
    /// s_φ per coordinate.
    pub sign_roll: Vec<f64>,
}

impl ActiveSuspension {
    /// The sign vectors from the rest geometry: for coordinate i, with
    /// `g_j = ∂u_jz/∂y_i` of each wheel j at rest and (x_j, y_j) its rest position,
    /// `s_θ,i = −sgn(Σ_j x_j·g_j)` and `s_φ,i = sgn(Σ_j y_j·g_j)`: positive θ
    /// (nose down) moves the front wheels down and the rear ones up relative
    /// to the body; positive φ (left side up) moves the left wheels up and the
    /// right ones down. Example 2 gives s_θ = [+1, +1, +1, +1],
    /// s_φ = [−1, +1, +1, −1], as MODEL.md §8 states.
    pub fn new(
        config: ActiveSuspensionConfig,
        sprung: &[bool],
        rest_xy_dz: &[Vec<(f64, f64, f64)>],
    ) -> Self {
        let sgn = |v: f64| {
            if v > 0.0 {
                1.0
            } else if v < 0.0 {
                -1.0
            } else {
                0.0
            }
        };
        let mut sign_pitch = Vec::new();
        let mut sign_roll = Vec::new();
        for (i, wheels) in rest_xy_dz.iter().enumerate() {
            let on = sprung.get(i).copied().unwrap_or(false);
            let sx: f64 = wheels.iter().map(|(x, _, g)| x * g).sum();
            let sy: f64 = wheels.iter().map(|(_, y, g)| y * g).sum();
            sign_pitch.push(if on { -sgn(sx) } else { 0.0 });
            sign_roll.push(if on { sgn(sy) } else { 0.0 });
        }
        Self {
            config,
            sign_pitch,
            sign_roll,
        }
    }

    /// One update of the neutrals `y0` (clamped to `[lo, hi]`) from pitch,
    /// roll and their Euler rates.
    pub fn update(
        &self,
        pitch: f64,
        pitch_rate: f64,
        roll: f64,
        roll_rate: f64,
        y0: &mut [f64],
        lo: &[f64],
        hi: &[f64],
    ) {
        let c = &self.config;
        let dp = c.kp_pitch * pitch + c.kd_pitch * pitch_rate;
        let dr = c.kp_roll * roll + c.kd_roll * roll_rate;
        for i in 0..y0.len() {
            if self.sign_pitch[i] == 0.0 && self.sign_roll[i] == 0.0 {
                continue;
            }
            y0[i] = (y0[i] + dp * self.sign_pitch[i] + dr * self.sign_roll[i]).clamp(lo[i], hi[i]);
        }
    }
}
