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
    /// Heading hold (ours, not the paper's), with optional line
    /// following: the torque difference of [`Steering::Slip`] or the
    /// Ackermann angles of the steerable wheels, from the heading error.
    Heading(HeadingHold),
}

impl Steering {
    /// Slip steering by a constant torque difference Δτ [N·m] (eq. 48);
    /// Δτ > 0 turns left.
    pub fn slip(delta_tau: f64) -> Self {
        Steering::Slip {
            delta_tau: Profile::Constant(delta_tau),
        }
    }
}

/// What a [`HeadingHold`] moves.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum HeadingActuator {
    /// A torque difference, `Δτ = K_p·e + K_i·∫e dt − K_d·ψ̇` (any rover).
    #[default]
    Slip,
    /// The steerable wheels at the curvature `κ = 2·sin(e)/L` that meets the
    /// commanded heading a lookahead L ahead (pure pursuit of a heading).
    Ackermann,
}

/// The set-point, line and gains of [`Steering::Heading`]. The heading
/// error is `e = wrap(ψ_cmd − ψ)` with
/// ```text
/// e_y   = −sin ψ_ref·(X − X_0) + cos ψ_ref·(Y − Y_0)   (left of the line > 0)
/// ψ_cmd = ψ_ref − atan(k_e·e_y + k_y·∫e_y dt)          (ψ_ref alone when k_e = 0)
/// ```
/// The integrals are states of the run ([`HeadingIntegrals`]), present
/// only when their gains are set.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct HeadingHold {
    /// `"slip"` (default) or `"ackermann"`.
    #[serde(default)]
    pub via: HeadingActuator,
    /// Heading set-point ψ_ref \[deg\] against time after settling (yaw,
    /// positive turns left); default 0, the X axis.
    #[serde(default)]
    pub heading_deg: Profile,
    /// Slip: torque difference per radian of heading error [N·m/rad], > 0;
    /// required with `via = "slip"`, not accepted with `"ackermann"`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub kp: Option<f64>,
    /// Slip: torque difference per rad/s of heading rate [N·m·s/rad], ≥ 0;
    /// default 0.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub kd: Option<f64>,
    /// Slip: torque difference per rad·s of integrated heading error
    /// [N·m/(rad·s)], ≥ 0; default 0 (no integral). It takes out the P law's
    /// steady heading offset under a steady yaw moment (a side slope).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub ki: Option<f64>,
    /// Ackermann: the lookahead L \[m\], > 0; required with
    /// `via = "ackermann"`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub lookahead: Option<f64>,
    /// Line following: heading correction per metre of lateral offset from
    /// the line through `line_origin` along ψ_ref, k_e \[rad/m\], ≥ 0;
    /// default 0 (heading alone; a rover sliding sideways down a slope keeps
    /// its heading but leaves its line). With a time table for ψ_ref the
    /// line turns about `line_origin` with it: a path of several legs needs
    /// one run per leg.
    #[serde(default)]
    pub cross_track: f64,
    /// Line following's integral gain k_y: heading correction per m·s of
    /// integrated lateral offset [rad/(m·s)], ≥ 0; default 0. A rover that
    /// must crab to hold its line (across a slope) holds it with a steady
    /// offset `tan(crab)/k_e` under `cross_track` alone; the integral
    /// supplies the crab angle instead and takes the offset out. Needs
    /// `cross_track > 0`. On waypoints it carries over from leg to leg.
    #[serde(default)]
    pub cross_track_integral: f64,
    /// A point of the line \[m\] (X, Y); default the origin.
    #[serde(default)]
    pub line_origin: [f64; 2],
    /// A path instead of one line: waypoints `[[X, Y], …]` \[m\], ≥ 2, each
    /// leg followed as a line (with `cross_track`) until G passes the
    /// perpendicular through its end, checked every
    /// [`LEG_CHECK_PERIOD`] (or at the active suspension's sample times);
    /// the last leg's line is held beyond its end. Replaces `heading_deg`
    /// and `line_origin`.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub waypoints: Vec<[f64; 2]>,
}

/// How often a heading hold on waypoints checks whether G has passed the
/// end of its leg \[s\] (a switch is a jump of the command: the integrator
/// restarts there, as at a step of a set-point).
pub const LEG_CHECK_PERIOD: f64 = 0.1;

impl HeadingHold {
    /// The line followed at time `tc` after settling on leg `leg`: its
    /// heading ψ_ref \[rad\] and a point of it.
    pub fn line(&self, tc: f64, leg: usize) -> (f64, [f64; 2]) {
        if self.waypoints.len() >= 2 {
            self.line_with(0.0, leg)
        } else {
            self.line_with(self.heading_deg.at(tc).to_radians(), leg)
        }
    }

    /// [`HeadingHold::line`] with the set-point ψ_ref \[rad\] already read
    /// (it is not read on waypoints).
    pub fn line_with(&self, heading: f64, leg: usize) -> (f64, [f64; 2]) {
        if self.waypoints.len() >= 2 {
            let k = leg.min(self.waypoints.len() - 2);
            let (a, b) = (self.waypoints[k], self.waypoints[k + 1]);
            ((b[1] - a[1]).atan2(b[0] - a[0]), a)
        } else {
            (heading, self.line_origin)
        }
    }

    /// Whether G at `position` has passed the end of leg `leg` and a next
    /// leg exists.
    pub fn passed(&self, leg: usize, position: [f64; 2]) -> bool {
        if leg + 2 >= self.waypoints.len() {
            return false;
        }
        let (a, b) = (self.waypoints[leg], self.waypoints[leg + 1]);
        let d = [b[0] - a[0], b[1] - a[1]];
        let along = d[0] * (position[0] - a[0]) + d[1] * (position[1] - a[1]);
        along >= d[0] * d[0] + d[1] * d[1]
    }

    /// Whether the law follows a line or a path (and a deviation from it
    /// means something): `cross_track > 0` or waypoints.
    pub fn follows_a_path(&self) -> bool {
        self.cross_track > 0.0 || !self.waypoints.is_empty()
    }

    /// Distance \[m\] of G at `position`, at time `tc` after settling, from
    /// the commanded path: the line, or the nearest leg of the waypoints
    /// (the last one extended beyond its end, as it is held there).
    pub fn deviation(&self, tc: f64, position: [f64; 2]) -> f64 {
        if self.waypoints.len() < 2 {
            return offset(self.line(tc, 0), position).abs();
        }
        let last = self.waypoints.len() - 2;
        (0..=last)
            .map(|k| {
                let (a, b) = (self.waypoints[k], self.waypoints[k + 1]);
                let d = [b[0] - a[0], b[1] - a[1]];
                let p = [position[0] - a[0], position[1] - a[1]];
                let t = (d[0] * p[0] + d[1] * p[1]) / (d[0] * d[0] + d[1] * d[1]);
                let t = if k == last {
                    t.max(0.0)
                } else {
                    t.clamp(0.0, 1.0)
                };
                (p[0] - t * d[0]).hypot(p[1] - t * d[1])
            })
            .fold(f64::INFINITY, f64::min)
    }

    /// The heading error e \[rad\] on `line` (from [`HeadingHold::line`])
    /// for G at (X, Y), heading ψ and the line offset's integral `∫e_y dt`.
    pub fn error(
        &self,
        line: (f64, [f64; 2]),
        position: [f64; 2],
        psi: f64,
        line_integral: f64,
    ) -> f64 {
        let reference = line.0;
        let command = if self.cross_track > 0.0 {
            let correction = self.cross_track * offset(line, position)
                + self.cross_track_integral * line_integral;
            reference - correction.atan()
        } else {
            reference
        };
        wrap_angle(command - psi)
    }

    /// The lateral offset e_y \[m\] of G at (X, Y) from `line`, left of it
    /// positive: what the line integral integrates.
    pub fn line_offset(&self, line: (f64, [f64; 2]), position: [f64; 2]) -> f64 {
        offset(line, position)
    }

    /// Slip: Δτ [N·m] on `line` for G at (X, Y), heading ψ, heading rate ψ̇
    /// and the integral states.
    pub fn delta_tau(
        &self,
        line: (f64, [f64; 2]),
        position: [f64; 2],
        psi: f64,
        psi_rate: f64,
        integrals: HeadingIntegrals,
    ) -> f64 {
        self.kp.unwrap_or(0.0) * self.error(line, position, psi, integrals.line)
            + self.ki.unwrap_or(0.0) * integrals.heading
            - self.kd.unwrap_or(0.0) * psi_rate
    }

    /// Ackermann: the path curvature κ \[1/m\] on `line`.
    pub fn curvature(
        &self,
        line: (f64, [f64; 2]),
        position: [f64; 2],
        psi: f64,
        integrals: HeadingIntegrals,
    ) -> f64 {
        match self.lookahead {
            Some(l) if l > 0.0 => 2.0 * self.error(line, position, psi, integrals.line).sin() / l,
            _ => 0.0,
        }
    }

    /// Whether the heading error is integrated (slip with `ki > 0`).
    pub fn integrates_heading(&self) -> bool {
        self.via == HeadingActuator::Slip && self.ki.is_some_and(|k| k > 0.0)
    }

    /// Whether the line offset is integrated (`cross_track_integral > 0`).
    pub fn integrates_line(&self) -> bool {
        self.cross_track_integral > 0.0
    }
}

/// The heading hold's integral states, ∫e dt \[rad·s\] and ∫e_y dt
/// \[m·s\]; 0 for an integral the law does not have.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct HeadingIntegrals {
    /// ∫e dt, the heading error's integral (slip, `ki`).
    pub heading: f64,
    /// ∫e_y dt, the line offset's integral (`cross_track_integral`).
    pub line: f64,
}

/// Largest heading correction the line integral builds up alone, as
/// `|k_y·∫e_y dt|` (1: 45° of crab): beyond it the integral stops growing
/// (anti-windup), so a rover pushed off its line by an obstacle does not
/// come back turned across it.
pub const LINE_INTEGRAL_CAP: f64 = 1.0;

/// The signed distance \[m\] of `position` from `line` (heading, point),
/// left of it positive: `e_y` of [`HeadingHold`].
fn offset(line: (f64, [f64; 2]), position: [f64; 2]) -> f64 {
    let (reference, origin) = line;
    let (s, c) = reference.sin_cos();
    -s * (position[0] - origin[0]) + c * (position[1] - origin[1])
}

/// `a` wrapped to (−π, π].
pub fn wrap_angle(a: f64) -> f64 {
    use std::f64::consts::{PI, TAU};
    let r = a.rem_euclid(TAU);
    if r > PI { r - TAU } else { r }
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
