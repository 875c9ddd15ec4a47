//! Active suspension (MODEL.md §8): the paper's eq. 42 (§5.2) and a
//! model-based leveling law (ours).

use rover_dynamics::Model;
use rover_dynamics::model::Spring;
use rover_dynamics::nalgebra::Matrix3;
use serde::{Deserialize, Serialize};

/// Which law moves the spring neutrals.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum SuspensionLaw {
    /// The paper's eq. 42: neutrals moved along sign vectors by pitch and
    /// roll (and their rates), clamped to the arms' travel.
    #[default]
    Eq42,
    /// Ours: pitch and roll levelled, the heave mode held at mid-travel and
    /// the warp mode sharing the load, each mode through the geometry of the
    /// loaded rover (MODEL.md §8).
    Leveling,
}

/// The `[control.active_suspension]` table.
///
/// `law = "eq42"` (default): every `sample_time` the pitch θ and roll φ and
/// their Euler rates are measured and the spring neutrals corrected:
/// ```text
/// y0 ← clamp(y0 + (K_p1·θ + K_d1·θ̇)·s_θ + (K_p2·φ + K_d2·φ̇)·s_φ, y_min, y_max)
/// ```
/// The law is incremental — an integral controller; gains are per update.
///
/// `law = "leveling"`: see [`Leveling`]; every gain has a default derived
/// from the rover.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ActiveSuspensionConfig {
    /// Update period Δt_c \[s\] (the paper's 0.1 s).
    #[serde(default = "default_sample")]
    pub sample_time: f64,
    /// The law (`"eq42"` or `"leveling"`).
    #[serde(default)]
    pub law: SuspensionLaw,
    /// eq42: pitch gain K_p1 [rad of y0 per rad, per update]; required.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub kp_pitch: Option<f64>,
    /// eq42: pitch-rate gain K_d1 [rad of y0 per rad/s, per update]; default 0.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub kd_pitch: Option<f64>,
    /// eq42: roll gain K_p2; required.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub kp_roll: Option<f64>,
    /// eq42: roll-rate gain K_d2; default 0.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub kd_roll: Option<f64>,
    /// leveling: fraction of the pitch and roll removed per update, in
    /// (0, 1]; default [`LEVELING_CROSSOVER_PER_UPDATE`] (see [`Leveling`]).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub attitude_gain: Option<f64>,
    /// leveling: body-plane correction per unit of pitch and roll rate, per
    /// update \[s\] (≥ 0); default `attitude_gain·τ_s`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub rate_gain: Option<f64>,
    /// leveling: fraction of the heave offset from mid-travel removed per
    /// update, in [0, 1]; default `Δt_c/(2·τ_s)` (at most 0.5).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub centring_gain: Option<f64>,
    /// leveling: fraction of the warp-mode load imbalance removed per update,
    /// in [0, 1]; default 0.5.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub warp_gain: Option<f64>,
}

fn default_sample() -> f64 {
    0.1
}

/// Crossover of the leveling law's pitch and roll loops, in radians per
/// update: the default `attitude_gain`. 0.3 rad per update keeps the phase
/// lost to the sample-and-hold (half an update, 0.15 rad ≈ 9°) small.
pub const LEVELING_CROSSOVER_PER_UPDATE: f64 = 0.3;

/// The model-based leveling law (ours), settled for one rover at its
/// static equilibrium on flat ground.
///
/// With `g_ij = ∂u_jz/∂y_i` at the equilibrium and (x_j, y_j) the wheels'
/// positions there, a change δy of the sprung coordinates with the wheels
/// held on the ground moves the body plane `z = h − x·θ + y·φ` by the
/// least-squares fit `E·δy` of the corner changes `−Σ_i g_ij·δy_i`
/// (E: 3 × m_s, rows heave, pitch, roll). Its pseudo-inverse E⁺ turns a
/// wanted body-plane change into arm motions; `W = I − E⁺E` projects onto
/// the warp modes, which move no body plane but share the load. Each update:
/// ```text
/// δh = c_h · E_h·(y_mid − y)                       (heave toward mid-travel)
/// δθ = −(a·θ + b·θ̇),  δφ = −(a·φ + b·φ̇)            (level)
/// y0 ← clamp(y0 + E⁺·[δh, δθ, δφ] − c_w·W·(y0 − y − d_s), n_min, n_max)
/// ```
/// d_s = y0 − y at the equilibrium (the static spring deflection), so the
/// warp term keeps each spring's deflection at its static share. The arm
/// follows its neutral through the spring and damper with the time constant
/// τ_s = c/k; the defaults a = 0.3, b = a·τ_s put the PI zero on that lag.
/// The neutral's range (the actuator's) is the arm's travel shifted by the
/// static deflection, so the loaded arm can reach either stop.
#[derive(Clone, Debug, PartialEq)]
pub struct Leveling {
    /// The sprung coordinates (indices into y).
    pub sprung: Vec<usize>,
    /// E⁺, m_s × 3, row-major.
    pub to_arms: Vec<[f64; 3]>,
    /// E's heave row (m per rad of each sprung coordinate).
    pub heave_row: Vec<f64>,
    /// W = I − E⁺E, m_s × m_s, row-major.
    pub warp: Vec<f64>,
    /// Mid-travel (in wheel height) of each sprung coordinate.
    pub mid: Vec<f64>,
    /// Static deflection d_s = y0 − y of each sprung coordinate.
    pub deflection: Vec<f64>,
    /// The arm's lag τ_s = c/k \[s\] (mean over the sprung coordinates).
    pub lag: f64,
    /// Gains a, b \[s\], c_h, c_w.
    pub gains: [f64; 4],
    /// Scratch (m_s): the warp error.
    scratch: Vec<f64>,
}

/// Mid-travel of coordinate `i` in wheel height: where the heights of the
/// wheels it moves (summed, the other coordinates at `y_eq`) lie halfway
/// between their values at the two travel limits, found by bisection. A
/// swing arm near its bottom dead centre moves its wheel little per
/// radian, so this lies nearer the top stop than the angular mid-travel.
/// Falls back to the angular mid-travel when the height is not monotonic.
fn mid_travel(model: &Model, y_eq: &[f64], i: usize, g: &[Vec<f64>]) -> f64 {
    let c = &model.coordinates[i];
    let mut y = y_eq.to_vec();
    let mut z = |v: f64| {
        y[i] = v;
        model
            .wheels
            .iter()
            .zip(g)
            .filter(|(_, gj)| gj[i] != 0.0)
            .map(|(w, _)| model.bodies[w.body].position.value(&y)[2])
            .sum::<f64>()
    };
    let angular = 0.5 * (c.min + c.max);
    let (z_lo, z_hi) = (z(c.min), z(c.max));
    let target = 0.5 * (z_lo + z_hi);
    let (mut a, mut b) = (c.min, c.max);
    for _ in 0..60 {
        let m = 0.5 * (a + b);
        if (z(m) - target) * (z_hi - z_lo) < 0.0 {
            a = m;
        } else {
            b = m;
        }
    }
    let mid = 0.5 * (a + b);
    // Monotonic between the stops: the height at each side of the root.
    let n = 32;
    let monotonic = (0..n).all(|k| {
        let v0 = c.min + (c.max - c.min) * k as f64 / n as f64;
        let v1 = c.min + (c.max - c.min) * (k + 1) as f64 / n as f64;
        (z(v1) - z(v0)) * (z_hi - z_lo) >= 0.0
    });
    if monotonic && z_hi != z_lo {
        mid
    } else {
        angular
    }
}

/// The running law: its configuration, what it needs of the rover and the
/// range of the neutrals it commands.
#[derive(Clone, Debug, PartialEq)]
pub struct ActiveSuspension {
    /// The configuration.
    pub config: ActiveSuspensionConfig,
    /// eq42: s_θ per coordinate (0 for coordinates without a spring).
    pub sign_pitch: Vec<f64>,
    /// eq42: s_φ per coordinate.
    pub sign_roll: Vec<f64>,
    /// The leveling law, when chosen.
    pub leveling: Option<Leveling>,
    /// Lowest neutral each coordinate may be given.
    pub lo: Vec<f64>,
    /// Highest neutral each coordinate may be given.
    pub hi: Vec<f64>,
}

/// What a leveling law needs of the rover that cannot be had.
#[derive(Clone, Debug, PartialEq)]
pub struct LevelingError(pub String);

impl ActiveSuspension {
    /// The paper's eq. 42 with sign vectors from the rest geometry: for
    /// coordinate i, with `g_j = ∂u_jz/∂y_i` of each wheel j at rest and
    /// (x_j, y_j) its rest position, `s_θ,i = −sgn(Σ_j x_j·g_j)` and
    /// `s_φ,i = sgn(Σ_j y_j·g_j)`: positive θ (nose down) moves the front
    /// wheels down and the rear ones up relative to the body; positive φ
    /// (left side up) moves the left wheels up and the right ones down.
    /// Example 2 gives s_θ = [+1, +1, +1, +1], s_φ = [−1, +1, +1, −1], as
    /// MODEL.md §8 states. The neutrals stay within the travel `[lo, hi]`.
    pub fn new(
        config: ActiveSuspensionConfig,
        sprung: &[bool],
        rest_xy_dz: &[Vec<(f64, f64, f64)>],
        lo: Vec<f64>,
        hi: Vec<f64>,
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
            leveling: None,
            lo,
            hi,
        }
    }

    /// The leveling law for `model`, settled at its static equilibrium on
    /// flat ground `y_eq` (coordinates). Gains left out of `config` get
    /// their defaults (see [`Leveling`]).
    pub fn leveling(
        config: ActiveSuspensionConfig,
        model: &Model,
        y_eq: &[f64],
    ) -> Result<Self, LevelingError> {
        let m = model.m();
        let sprung: Vec<usize> = (0..m)
            .filter(|&i| !matches!(model.coordinates[i].spring, Spring::None))
            .collect();
        let ms = sprung.len();
        // Wheel positions and slopes at the equilibrium.
        let mut xy = Vec::new();
        let mut g = Vec::new(); // per wheel: ∂u_z/∂y_i for every coordinate
        for w in &model.wheels {
            let body = &model.bodies[w.body];
            let mut dz = vec![0.0; m];
            let u = body.position.eval(y_eq, |i, d1, _| dz[i] += d1[2]);
            xy.push((u[0], u[1]));
            g.push(dz);
        }
        let n = xy.len();
        if n < 3 {
            return Err(LevelingError(format!(
                "the rover has {n} wheels; leveling a body plane needs at least 3"
            )));
        }
        // Least-squares plane through the corner changes: rows of Φ are
        // [1, −x_j, y_j]; E = (ΦᵀΦ)⁻¹Φᵀ·C with C_jk = −g_j,sprung[k].
        let row = |j: usize| [1.0, -xy[j].0, xy[j].1];
        let ptp: Matrix3<f64> =
            Matrix3::from_fn(|r, c| (0..n).map(|j| row(j)[r] * row(j)[c]).sum());
        let fit = ptp.try_inverse().ok_or_else(|| {
            LevelingError("the wheels are in a line, so they define no body plane to level".into())
        })?;
        // e[r][k]: body-plane change r per unit of sprung coordinate k.
        let mut e = vec![[0.0_f64; 3]; ms];
        for (k, &i) in sprung.iter().enumerate() {
            let mut rhs = [0.0; 3];
            for (j, gj) in g.iter().enumerate() {
                for (r, v) in rhs.iter_mut().enumerate() {
                    *v += row(j)[r] * -gj[i];
                }
            }
            for r in 0..3 {
                e[k][r] = (0..3).map(|c| fit[(r, c)] * rhs[c]).sum();
            }
        }
        let eet: Matrix3<f64> = Matrix3::from_fn(|r, c| e.iter().map(|ek| ek[r] * ek[c]).sum());
        let scale = eet.trace().max(f64::MIN_POSITIVE);
        let inv = (eet + Matrix3::identity() * (1e-9 * scale))
            .try_inverse()
            .ok_or_else(|| {
                LevelingError("the sprung coordinates move no wheel up or down".into())
            })?;
        for (mode, name) in [(1, "pitch"), (2, "roll")] {
            let reach: f64 = e.iter().map(|ek| ek[mode].abs()).sum();
            if reach < 1e-9 {
                return Err(LevelingError(format!(
                    "no sprung coordinate moves the body in {name}, so the law cannot level it; use law = \"eq42\" or a rover with springs at both ends and both sides"
                )));
            }
        }
        // E⁺ = Eᵀ(EEᵀ)⁻¹ (ms × 3) and W = I − E⁺E (ms × ms).
        let pinv: Vec<[f64; 3]> = e
            .iter()
            .map(|ek| {
                let mut p = [0.0; 3];
                for (c, v) in p.iter_mut().enumerate() {
                    *v = (0..3).map(|r| ek[r] * inv[(r, c)]).sum();
                }
                p
            })
            .collect();
        let mut w = vec![0.0; ms * ms];
        for a in 0..ms {
            for b in 0..ms {
                let pe: f64 = (0..3).map(|r| pinv[a][r] * e[b][r]).sum();
                w[a * ms + b] = f64::from(u8::from(a == b)) - pe;
            }
        }
        let mut lag_sum = 0.0;
        let mut deflection = Vec::with_capacity(ms);
        let mut lo: Vec<f64> = model.coordinates.iter().map(|c| c.min).collect();
        let mut hi: Vec<f64> = model.coordinates.iter().map(|c| c.max).collect();
        for &i in &sprung {
            let c = &model.coordinates[i];
            let d = c.neutral - y_eq[i];
            // Spring rate at the static deflection: −∂Q/∂y.
            let h = 1e-6;
            let q = |y: f64| rover_dynamics::forces::coordinate_force(c, c.neutral, y, 0.0);
            let k = -(q(y_eq[i] + h) - q(y_eq[i] - h)) / (2.0 * h);
            if k.is_nan() || k <= 0.0 {
                return Err(LevelingError(format!(
                    "coordinate y{} has no stiffness at its static deflection, so moving its neutral moves nothing",
                    i + 1
                )));
            }
            lag_sum += c.damping / k;
            deflection.push(d);
            lo[i] = c.min + d.min(0.0);
            hi[i] = c.max + d.max(0.0);
        }
        let lag = lag_sum / ms as f64;
        let t = config.sample_time;
        let a = config
            .attitude_gain
            .unwrap_or(LEVELING_CROSSOVER_PER_UPDATE);
        let b = config.rate_gain.unwrap_or(a * lag);
        let ch = config
            .centring_gain
            .unwrap_or_else(|| (t / (2.0 * lag.max(t))).min(0.5));
        let cw = config.warp_gain.unwrap_or(0.5);
        let leveling = Leveling {
            mid: sprung
                .iter()
                .map(|&i| mid_travel(model, y_eq, i, &g))
                .collect(),
            to_arms: pinv,
            heave_row: e.iter().map(|ek| ek[0]).collect(),
            warp: w,
            sprung,
            deflection,
            lag,
            gains: [a, b, ch, cw],
            scratch: vec![0.0; ms],
        };
        Ok(Self {
            config,
            sign_pitch: vec![0.0; m],
            sign_roll: vec![0.0; m],
            leveling: Some(leveling),
            lo,
            hi,
        })
    }

    /// One update of the neutrals `y0` from pitch, roll, their Euler rates
    /// and the coordinates `y`. Allocates nothing.
    pub fn update(
        &mut self,
        pitch: f64,
        pitch_rate: f64,
        roll: f64,
        roll_rate: f64,
        y: &[f64],
        y0: &mut [f64],
    ) {
        let (lo, hi) = (&self.lo, &self.hi);
        if let Some(l) = &mut self.leveling {
            let [a, b, ch, cw] = l.gains;
            let ms = l.sprung.len();
            let mut heave = 0.0;
            for k in 0..ms {
                heave += l.heave_row[k] * (l.mid[k] - y[l.sprung[k]]);
                let i = l.sprung[k];
                l.scratch[k] = y0[i] - y[i] - l.deflection[k];
            }
            let cmd = [
                ch * heave,
                -(a * pitch + b * pitch_rate),
                -(a * roll + b * roll_rate),
            ];
            for k in 0..ms {
                let i = l.sprung[k];
                let r = &l.to_arms[k];
                let mut dy = r[0] * cmd[0] + r[1] * cmd[1] + r[2] * cmd[2];
                for (wk, s) in l.warp[k * ms..(k + 1) * ms].iter().zip(&l.scratch) {
                    dy -= cw * wk * s;
                }
                y0[i] = (y0[i] + dy).clamp(lo[i], hi[i]);
            }
            return;
        }
        let c = &self.config;
        let dp = c.kp_pitch.unwrap_or(0.0) * pitch + c.kd_pitch.unwrap_or(0.0) * pitch_rate;
        let dr = c.kp_roll.unwrap_or(0.0) * roll + c.kd_roll.unwrap_or(0.0) * roll_rate;
        for i in 0..y0.len() {
            if self.sign_pitch[i] == 0.0 && self.sign_roll[i] == 0.0 {
                continue;
            }
            y0[i] = (y0[i] + dp * self.sign_pitch[i] + dr * self.sign_roll[i]).clamp(lo[i], hi[i]);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The paper's law, step by step: one update moves each neutral by
    /// `(K_p1·θ + K_d1·θ̇)·s_θ + (K_p2·φ + K_d2·φ̇)·s_φ`, clamps it to the
    /// arm's travel and leaves an unsprung coordinate alone.
    #[test]
    fn eq42_moves_the_neutrals_along_its_sign_vectors_within_the_travel() {
        let config = ActiveSuspensionConfig {
            sample_time: 0.1,
            law: SuspensionLaw::Eq42,
            kp_pitch: Some(0.6),
            kd_pitch: Some(0.05),
            kp_roll: Some(0.4),
            kd_roll: Some(0.02),
            attitude_gain: None,
            rate_gain: None,
            centring_gain: None,
            warp_gain: None,
        };
        // Example 2's layout: FL, FR (g < 0), RL, RR (g > 0), and a free
        // coordinate carrying no wheel.
        let wheels = vec![
            vec![(0.18, 0.2, -0.17)],
            vec![(0.18, -0.2, -0.17)],
            vec![(-0.22, 0.2, 0.17)],
            vec![(-0.22, -0.2, 0.17)],
            vec![],
        ];
        let sprung = [true, true, true, true, false];
        let lo = vec![-1.0, -1.0, 0.03, 0.03, -1.0];
        let hi = vec![-0.03, -0.03, 1.0, 1.0, 1.0];
        let mut law = ActiveSuspension::new(config, &sprung, &wheels, lo, hi);
        assert_eq!(law.sign_pitch, [1.0, 1.0, 1.0, 1.0, 0.0]);
        assert_eq!(law.sign_roll, [-1.0, 1.0, 1.0, -1.0, 0.0]);
        let y0_start = [-0.3, -0.3, 0.3, 0.3, 0.0];
        let mut y0 = y0_start;
        let (pitch, pitch_rate, roll, roll_rate) = (0.01, -0.2, 0.02, 0.5);
        law.update(pitch, pitch_rate, roll, roll_rate, &[0.0; 5], &mut y0);
        let dp = 0.6 * pitch + 0.05 * pitch_rate;
        let dr = 0.4 * roll + 0.02 * roll_rate;
        let want = [
            -0.3 + dp - dr,
            -0.3 + dp + dr,
            0.3 + dp + dr,
            0.3 + dp - dr,
            0.0,
        ];
        for (got, want) in y0.iter().zip(want) {
            assert!((got - want).abs() < 1e-15, "{y0:?} vs {want:?}");
        }
        // A large pitch drives every neutral to its travel limit, no further.
        law.update(10.0, 0.0, 0.0, 0.0, &[0.0; 5], &mut y0);
        assert_eq!(y0, [-0.03, -0.03, 1.0, 1.0, 0.0]);
    }
}
